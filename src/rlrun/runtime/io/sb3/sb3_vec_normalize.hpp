#pragma once
// SB3's VecNormalize statistics saved beside a model (`vec_env.save("vecnormalize.pkl")`;
// rl-zoo writes <run>/<env>/vecnormalize.pkl next to <run>/<env>.zip): a pickle of the
// VecNormalize object without its envs (stable_baselines3/common/vec_env/vec_normalize.py
// __getstate__), read without running it (core/pickle_reader.hpp) into what rlrun keeps in a
// model file for its own `env.normalize` (wrappers/vec_normalize.hpp): the setting
// (norm_obs, norm_reward, clip_obs, clip_reward, gamma, epsilon) and the running statistics
// (obs_rms, ret_rms: RunningMeanStd's mean, var, count) as `wrappers/NormalizeObservation/...`
// and `wrappers/NormalizeReward/...` tensors, frozen when the model is played.
#include <optional>
#include <string>

#include "rlrun/tensor.hpp"
#include "rlrun/wrappers/vec_normalize.hpp"

namespace rlrun {

// The file beside an SB3 model: `<dir>/vecnormalize.pkl`, else rl-zoo's
// `<dir>/<stem>/vecnormalize.pkl` (model `<dir>/<stem>.zip`), else, in an rl-zoo run folder
// `<env>_<n>/`, `<env>_<n>/<env>/vecnormalize.pkl` (its best model and checkpoints), if it
// exists.
std::optional<std::string> find_sb3_vec_normalize(const std::string& model_path);

struct Sb3VecNormalize {
  NormalizeSetting setting;
  TensorMap statistics;
};

// Throws RuntimeFailure naming `path` for a file that is not such a pickle, names a global
// outside its allowlist, or holds statistics that are not finite or do not fit
// `observation_dim` (the model's observation size).
Sb3VecNormalize read_sb3_vec_normalize(const std::string& path, int64_t observation_dim);

}  // namespace rlrun
