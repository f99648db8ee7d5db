#pragma once
// The critics' regression target of TD3 (Fujimoto et al. 2018, arXiv:1802.09477, eq. 15 and
// "target policy smoothing") as SB3 td3/td3.py TD3.train computes it under th.no_grad():
//   noise  = clamp(N(0, target_policy_noise), -target_noise_clip, target_noise_clip)
//   a'     = clamp(actor_target(s') + noise, -1, 1)
//   y      = r + (1 - done) * gamma * min_i Q_target_i(s', a')
// DDPG is the same with one critic and no smoothing (SB3 ddpg/ddpg.py: target_noise_clip 0).
// Everything is float32 like the torch tensors; `done` is 1 only for true terminations (the
// replay buffer stores time-limit truncations as 0 so that they bootstrap).
#include <Eigen/Core>
#include <vector>

#include "rlrun/rng.hpp"

namespace rlrun {

// Fills `noise` (already sized action_dim x batch) with the clipped smoothing noise. With
// noise_std or noise_clip 0 it is exactly zero and no random numbers are drawn.
void sample_target_smoothing_noise(Rng& rng, float noise_std, float noise_clip,
                                   Eigen::MatrixXf& noise);

// next_actions = clamp(target_actions + noise, -1, 1).
void smoothed_target_actions(const Eigen::Ref<const Eigen::MatrixXf>& target_actions,
                             const Eigen::Ref<const Eigen::MatrixXf>& noise,
                             Eigen::MatrixXf& next_actions);

// y = r + (1 - done) * gamma * min_i next_q[i], each 1 x n; y must already be 1 x n (it may be
// a block of a whole batch's row). Throws std::invalid_argument on mismatched sizes.
void td3_target(const std::vector<const Eigen::MatrixXf*>& next_q,
                const Eigen::Ref<const Eigen::RowVectorXf>& rewards,
                const Eigen::Ref<const Eigen::RowVectorXf>& dones, float gamma,
                Eigen::Ref<Eigen::MatrixXf> y);

}  // namespace rlrun
