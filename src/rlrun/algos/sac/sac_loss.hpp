#pragma once
// The element-wise parts of SAC's update (SB3 sac/sac.py train; CleanRL
// sac_continuous_action.py), separated from the networks so that they read like the Python
// and can be checked on hand-made numbers. All rows are 1 x n; per-critic values arrive as one
// 1 x n matrix per critic.
#include <Eigen/Core>
#include <vector>

namespace rlrun {

// Soft Bellman target (th.no_grad block of SAC.train):
//   y = r + (1 - done) * gamma * (min_i Q_target_i(s', a') - alpha * log pi(a'|s'))
// `dones` already has time-limit truncations cleared (replay buffer, handle_timeout_termination).
// `target` must already be 1 x n (it may be a block of a whole batch's row). Throws
// std::invalid_argument on mismatched sizes.
void sac_critic_target(const Eigen::Ref<const Eigen::RowVectorXf>& rewards,
                       const Eigen::Ref<const Eigen::RowVectorXf>& dones,
                       const std::vector<const Eigen::MatrixXf*>& next_q_values,
                       const Eigen::Ref<const Eigen::RowVectorXf>& next_log_prob, float ent_coef,
                       float gamma, Eigen::Ref<Eigen::MatrixXf> target);

// Actor loss = mean_j(alpha * log_prob_j - min_i Q_i(s_j, a_j)) over a batch of B samples and
// its partial derivatives, for the n samples given (all of them, or one lane's part):
// grad_q[i] (1 x n) is -1/B where critic i gives the minimum (the first one on ties, like
// torch.min's index) and 0 elsewhere; grad_log_prob (1 x n) = alpha / B. Returns these
// samples' part of the loss, sum_j (...) / B. inv_batch = 1 / B.
double sac_actor_loss(const std::vector<const Eigen::MatrixXf*>& q_values,
                      const Eigen::Ref<const Eigen::RowVectorXf>& log_prob, float ent_coef,
                      float inv_batch, std::vector<Eigen::MatrixXf>& grad_q,
                      Eigen::RowVectorXf& grad_log_prob);

}  // namespace rlrun
