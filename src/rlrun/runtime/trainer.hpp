#pragma once
// Runs one experiment end to end: run directory, resolved config.yaml, envs with monitor
// files, the algorithm, logging (progress.csv, console, log.txt), periodic evaluation
// (evaluations.csv, best_model.zip), and model.zip at the end or on Ctrl-C.
#include <string>

#include "rlrun/runtime/experiment.hpp"

namespace rlrun {

struct TrainOutcome {
  std::string run_dir;
  std::string model_path;
  int64_t timesteps = 0;
  double wall_seconds = 0;
  bool interrupted = false;
};

TrainOutcome train_experiment(const Experiment& experiment, const Registry& registry);

// Set by SIGINT/SIGTERM; training stops at the next env step and saves its model.
void install_interrupt_handlers();
bool interrupt_requested();

}  // namespace rlrun
