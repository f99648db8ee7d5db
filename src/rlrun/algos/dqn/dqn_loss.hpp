#pragma once
// The DQN loss of SB3 dqn/dqn.py DQN.train, split into its two halves so that each can be
// tested on its own:
//   target  = r + (1 - done) * gamma * max_a' Q_target(s', a')   (no gradient)
//   loss    = smooth_l1(Q(s, a), target), mean over the batch   (F.smooth_l1_loss, beta = 1)
// "done" is the replay buffer's flag, already 0 for time-limit truncations (SB3
// handle_timeout_termination), so truncated transitions bootstrap and terminal ones do not.
// Outputs are written into caller-sized storage (a column range of a larger batch works too).
#include <Eigen/Core>

namespace rlrun {

// next_q: n_actions x batch (the target network's output on next_obs); targets: 1 x batch.
void dqn_td_targets(const Eigen::Ref<const Eigen::MatrixXf>& next_q,
                    const Eigen::Ref<const Eigen::RowVectorXf>& rewards,
                    const Eigen::Ref<const Eigen::RowVectorXf>& dones, float gamma,
                    Eigen::Ref<Eigen::RowVectorXf> targets);

// q: n_actions x batch (the online network's output on obs); actions: 1 x batch action indices
// (as floats, like the replay buffer stores them). Returns the mean Huber loss and writes its
// gradient with respect to q into grad_q (n_actions x batch; zero except at the taken actions,
// where it is clamp(q - target, -1, 1) / batch). `mean_over` replaces the batch size as the
// divisor (loss and gradient) when q holds one part of a larger batch split across threads.
// Throws std::out_of_range for an action index outside [0, n_actions).
double dqn_huber_loss(const Eigen::Ref<const Eigen::MatrixXf>& q,
                      const Eigen::Ref<const Eigen::MatrixXf>& actions,
                      const Eigen::Ref<const Eigen::RowVectorXf>& targets,
                      Eigen::Ref<Eigen::MatrixXf> grad_q, Eigen::Index mean_over = 0);

}  // namespace rlrun
