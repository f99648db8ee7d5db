#pragma once
// `env.normalize`: SB3's VecNormalize (stable_baselines3/common/vec_env/vec_normalize.py) on
// the training envs as one key, as rl-zoo's `normalize:` hyperparameter
// (rl_zoo3/exp_manager.py _preprocess_normalization, create_envs):
//     normalize: true                     # observations and rewards, VecNormalize's defaults
//     normalize: {norm_obs: true, norm_reward: false, clip_obs: 10.0, gamma: null, ...}
// It is built from the NormalizeObservation and NormalizeReward wrappers (their statistics are
// saved in the model file and frozen at evaluation: runtime/experiment/env_statistics.hpp), placed where
// VecNormalize sits: outermost, above the Monitor and the user's wrappers. In a training VecEnv
// a step hook does VecNormalize.step_wait's work for the whole batch: the observation
// statistics are updated with every env's observation at once, then all envs are normalised
// with the same statistics (terminal observations too); every env's reward is added to its
// discounted return, ret_rms is updated with the batch of returns, then the rewards are
// scaled. Evaluation envs are frozen and leave rewards unscaled (rl-zoo's eval env has
// norm_reward=False; episode returns come from the Monitor in any case).
// `gamma: null` is the algorithm's gamma (rl-zoo passes hyperparams["gamma"]), 0.99 for an
// algorithm without one (VecNormalize's default).
#include <optional>

#include "rlrun/core/config_checks.hpp"
#include "rlrun/core/config_fields.hpp"
#include "rlrun/env.hpp"
#include "rlrun/env/vec_env.hpp"

namespace rlrun {

struct NormalizeSetting {
  bool enabled = false;         // false: no normalisation (the key's default)
  bool norm_obs = true;         // SB3 VecNormalize norm_obs
  bool norm_reward = true;      // SB3 VecNormalize norm_reward
  double clip_obs = 10.0;       // SB3 VecNormalize clip_obs
  double clip_reward = 10.0;    // SB3 VecNormalize clip_reward
  std::optional<double> gamma;  // null: the algorithm's gamma
  double epsilon = 1e-8;        // SB3 VecNormalize epsilon
  template <class V>
  void visit(V& v) {
    v("norm_obs", norm_obs, "normalise observations with their running mean and std");
    v("norm_reward", norm_reward, "scale rewards by the running std of the discounted return");
    v("clip_obs", clip_obs, "normalised observations are clipped to [-clip_obs, clip_obs]",
      positive());
    v("clip_reward", clip_reward, "scaled rewards are clipped to [-clip_reward, clip_reward]",
      positive());
    v("gamma", gamma, "discount of the return whose std scales rewards (null = the algorithm's)",
      unit_interval());
    v("epsilon", epsilon, "added to the variances before the square root", positive());
  }
};

// `true` / `false`, or a map of the fields above (enabled).
void decode(const ConfigNode& n, NormalizeSetting& out);
// `false`, or the map with every field.
YAML::Node encode(const NormalizeSetting& v);

// Wraps one env copy with NormalizeObservation / NormalizeReward as `setting` says (`gamma`:
// the resolved discount). Does nothing when the setting is off.
EnvPtr add_normalization(EnvPtr env, const NormalizeSetting& setting, double gamma);

// Puts the outermost env.normalize wrappers of every copy in batched mode and installs the
// VecNormalize step hook. Call on a VecEnv whose copies came from add_normalization with the
// same setting, nothing wrapped above them.
void install_batch_normalization(VecEnv& env, const NormalizeSetting& setting);

}  // namespace rlrun
