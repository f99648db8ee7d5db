#include "rlrun/runtime/callback.hpp"

#include "rlrun/runtime/experiment.hpp"

#include "rlrun/runtime/checkpoint_callback.hpp"
#include "rlrun/runtime/eval_callback.hpp"
#include "rlrun/runtime/obs_log_callback.hpp"
#include "rlrun/runtime/video_callback.hpp"

namespace rlrun {

std::vector<std::unique_ptr<Callback>> make_callbacks(TrainingContext& context) {
  std::vector<std::unique_ptr<Callback>> callbacks;
  const Experiment& e = context.experiment;
  if (e.eval.freq > 0) callbacks.push_back(std::make_unique<EvalCallback>(context));
  if (e.checkpoint.freq > 0) callbacks.push_back(std::make_unique<CheckpointCallback>(context));
  if (e.obs_log.freq > 0) callbacks.push_back(std::make_unique<ObsLogCallback>(context));
  if (e.video.freq > 0) callbacks.push_back(std::make_unique<VideoCallback>(context));
  return callbacks;
}

}  // namespace rlrun
