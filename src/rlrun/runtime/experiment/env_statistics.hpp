#pragma once
// Finds the wrappers with model statistics (wrappers/model_statistics.hpp: NormalizeObservation,
// NormalizeReward) in an env stack and moves their statistics between envs and model files.
// In a model file they are tensors `wrappers/<name>/<field>` (e.g.
// `wrappers/NormalizeObservation/mean`, `.../var`, `.../count`, float64); a second wrapper of
// the same kind is `<name>.1`, and so on, in the order of `env.wrappers`.
#include <vector>

#include "rlrun/core/tensor.hpp"
#include "rlrun/env/vec_env.hpp"
#include "rlrun/env/wrapper.hpp"
#include "rlrun/wrappers/model_statistics.hpp"

namespace rlrun {

inline constexpr const char* kWrapperStatisticsPrefix = "wrappers/";

// The wrappers of `env`'s stack, outermost first, and the first of type W (nullptr if none).
std::vector<Wrapper*> wrapper_chain(Env& env);
template <class W>
W* find_wrapper(Env& env) {
  for (Wrapper* w : wrapper_chain(env))
    if (auto* found = dynamic_cast<W*>(w)) return found;
  return nullptr;
}

// The statistics wrappers in YAML order (innermost first).
std::vector<ModelStatistics*> model_statistics(Env& env);

// Makes envs 1..n-1 use env 0's statistics objects (VecNormalize keeps one set for all envs).
void share_model_statistics(VecEnv& env);

// Adds `wrappers/...` tensors for every statistics wrapper of `env` (none: adds nothing).
void save_model_statistics(Env& env, TensorMap& tensors);

// Loads them into `env`'s wrappers and sets their training flag. Throws StateMismatch naming
// the missing or mismatching tensor.
void load_model_statistics(Env& env, const TensorMap& tensors, bool training);

void set_statistics_training(Env& env, bool training);

}  // namespace rlrun
