#pragma once
// `run.init_from: model.zip` (`rlrun train --init-from model.zip`): a new run that starts from
// trained weights — SB3's `model = PPO.load(path, env=new_env); model.learn(...)` with fresh
// counters — e.g. train on a reward-shaped env, then fine-tune on the original reward, or on
// another env with the same spaces. The weights must come from the same algorithm with the
// same network shapes; the spaces must match. Normalisation statistics in the file are loaded
// into the new run's NormalizeObservation / NormalizeReward wrappers (still updating) when the
// new run has the same ones. Optimizer moments start fresh: model files do not hold them
// (checkpoints do; use --resume to continue a run exactly).
#include <string>

#include "rlrun/algos/algorithm.hpp"
#include "rlrun/env/vec_env.hpp"

namespace rlrun {

// Loads `path` into `algorithm` (and the statistics into env 0's shared wrappers). Returns a
// line for the log. Throws UsageError naming the file and why it does not fit this run.
std::string initialize_from_model(const std::string& path, Algorithm& algorithm, VecEnv& env);

}  // namespace rlrun
