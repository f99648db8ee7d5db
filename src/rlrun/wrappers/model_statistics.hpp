#pragma once
// Wrappers whose running statistics belong to the trained model: NormalizeObservation and
// NormalizeReward. SB3 keeps them in a VecNormalize object saved beside the model
// (rl-zoo's vecnormalize.pkl) and users lose or mismatch that file; rlrun stores them inside
// the model file (`wrappers/<name>/mean.npy`, ...) and `rlrun eval` loads them frozen.
//
// The n env copies of a training VecEnv share one statistics object (SB3's VecNormalize has
// one for all envs): share_statistics_with() makes this wrapper use `first`'s statistics.
// runtime/experiment/env_statistics.hpp finds these wrappers in an env stack and does the bookkeeping.
#include <string>

#include "rlrun/core/state_dict.hpp"

namespace rlrun {

class ModelStatistics {
 public:
  virtual ~ModelStatistics() = default;
  // Key prefix in model files, e.g. "NormalizeObservation".
  virtual std::string statistics_name() const = 0;
  virtual void save_statistics(StateWriter& out) const = 0;
  // Throws StateMismatch when a value is missing or has another shape.
  virtual void load_statistics(const StateReader& in) = 0;
  // SB3's VecNormalize.training: false freezes the statistics (evaluation, recording).
  virtual void set_training(bool training) = 0;
  virtual bool training() const = 0;
  // Uses `first`'s statistics from now on; throws std::invalid_argument if `first` is another
  // kind of wrapper or has another dimension.
  virtual void share_statistics_with(ModelStatistics& first) = 0;
  // Whether step() and reset() update the statistics themselves (shared by a VecEnv's copies, so
  // those copies cannot step at once) rather than leave them to a batch update after the step.
  virtual bool steps_update_statistics() const = 0;
};

}  // namespace rlrun
