#pragma once
// What a training session ends with (runtime/run/trainer.hpp's train_experiment, and a per-agent
// run's team, runtime/run/per_agent_training.hpp).
#include <cstdint>
#include <string>

#include "rlrun/runtime/io/session_summary.hpp"

namespace rlrun {

struct TrainOutcome {
  std::string run_dir;
  std::string model_path;
  int64_t start_timesteps = 0;  // the step count this session began at (a resumed run's checkpoint)
  int64_t timesteps = 0;        // ... and ended at: the run's total
  double wall_seconds = 0;      // this session's training time
  bool interrupted = false;
  std::string checkpoint_path;  // written on interruption: resume from it
  std::string stop_reason;      // set when a callback stopped training early
};

// The session's summary line's numbers (runtime/io/session_summary.hpp).
inline SessionSummary session_summary(const TrainOutcome& outcome) {
  return {outcome.interrupted, outcome.start_timesteps, outcome.timesteps, outcome.wall_seconds};
}

}  // namespace rlrun
