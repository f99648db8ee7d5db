#pragma once
// Generalised Advantage Estimation (Schulman et al. 2016) exactly as SB3's
// RolloutBuffer.compute_returns_and_advantage (stable_baselines3/common/buffers.py).
// Arrays are n_steps x n_envs (row = time step). episode_starts[t] = 1 where obs t began a new
// episode; `last_dones` are the dones of the final step. Timeout bootstrapping happens before,
// in the rollout (rewards of truncated steps already include gamma * V(final_obs)).
#include <Eigen/Core>

namespace rlrun {

using StepEnvMatrix = Eigen::Matrix<float, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

inline void compute_gae(const StepEnvMatrix& rewards, const StepEnvMatrix& values,
                        const StepEnvMatrix& episode_starts,
                        const Eigen::Ref<const Eigen::RowVectorXf>& last_values,
                        const Eigen::Ref<const Eigen::RowVectorXf>& last_dones, float gamma,
                        float gae_lambda, StepEnvMatrix& advantages, StepEnvMatrix& returns) {
  const Eigen::Index n_steps = rewards.rows();
  for (Eigen::Index env = 0; env < rewards.cols(); ++env) {
    float last_gae = 0.0f;
    for (Eigen::Index t = n_steps - 1; t >= 0; --t) {
      const bool last = t == n_steps - 1;
      const float next_non_terminal = 1.0f - (last ? last_dones(env) : episode_starts(t + 1, env));
      const float next_value = last ? last_values(env) : values(t + 1, env);
      const float delta = rewards(t, env) + gamma * next_value * next_non_terminal - values(t, env);
      last_gae = delta + gamma * gae_lambda * next_non_terminal * last_gae;
      advantages(t, env) = last_gae;
    }
  }
  returns = advantages + values;
}

}  // namespace rlrun
