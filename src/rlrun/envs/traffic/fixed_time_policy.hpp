#pragma once
// The traffic task's baseline: a fixed-time signal plan cycling North -> South -> East -> West,
// each approach green for `green_time` seconds (rounded up to whole decisions of the env's
// delta_time), the yellow the env inserts on every switch included, as a traffic engineer's
// pre-timed plan (the course's comparison for the DQN agent; sumo-rl's `fixed_ts`).
#include <Eigen/Core>
#include <functional>

#include "rlrun/env.hpp"

namespace rlrun {

class FixedTimePolicy {
 public:
  // Throws std::invalid_argument unless green_time and delta_time are positive.
  FixedTimePolicy(int green_time, int delta_time);

  // The action of the next decision; the cycle restarts with North at every episode start
  // (`episode_start` true on the first decision after a reset).
  int next_action(bool episode_start);

 private:
  int decisions_per_green_;
  int decision_ = 0;
};

// The plan as a policy acting on `env` (eval --baseline, record --policy fixed-time), its
// delta_time read from the env. Throws UsageError unless the innermost env is
// TrafficSignal-v0.
std::function<void(const Eigen::MatrixXf& obs, Eigen::MatrixXf& action)> fixed_time_actions(
    Env& env, int green_time);

}  // namespace rlrun
