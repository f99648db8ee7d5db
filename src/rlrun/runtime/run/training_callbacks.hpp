#pragma once
// The callbacks an experiment's sections turn on, each given its own section (eval,
// checkpoint, obs_log, video, in that order) and the trainer's narrow TrainingContext.
#include <memory>
#include <vector>

#include "rlrun/runtime/experiment/experiment.hpp"
#include "rlrun/runtime/run/callback.hpp"

namespace rlrun {

std::vector<std::unique_ptr<Callback>> make_callbacks(const Experiment& experiment,
                                                      TrainingContext& context);

}  // namespace rlrun
