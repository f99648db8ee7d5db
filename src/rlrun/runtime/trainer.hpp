#pragma once
// Runs one experiment end to end: run directory, resolved config.yaml, envs with monitor
// files, the algorithm, logging (progress.csv, console, log.txt), the callbacks the config
// turns on (runtime/callback.hpp: eval, checkpoint, obs_log), and model.zip at the end, after
// an early stop or on Ctrl-C. Model files hold the normalisation statistics.
#include <string>

#include "rlrun/runtime/experiment.hpp"

namespace rlrun {

struct TrainOutcome {
  std::string run_dir;
  std::string model_path;
  int64_t timesteps = 0;
  double wall_seconds = 0;
  bool interrupted = false;
  std::string stop_reason;  // set when a callback stopped training early
};

TrainOutcome train_experiment(const Experiment& experiment, const Registry& registry);

// Set by SIGINT/SIGTERM; training stops at the next env step and saves its model.
void install_interrupt_handlers();
bool interrupt_requested();

}  // namespace rlrun
