#include "rlrun/algos/dqn/dqn_loss.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace rlrun {

void dqn_td_targets(const Eigen::Ref<const Eigen::MatrixXf>& next_q,
                    const Eigen::Ref<const Eigen::RowVectorXf>& rewards,
                    const Eigen::Ref<const Eigen::RowVectorXf>& dones, float gamma,
                    Eigen::Ref<Eigen::RowVectorXf> targets) {
  const Eigen::Index batch = next_q.cols();
  if (targets.size() != batch || rewards.size() != batch || dones.size() != batch)
    throw std::invalid_argument("dqn_td_targets: batch sizes differ");
  for (Eigen::Index j = 0; j < batch; ++j) {
    // next_q_values.max(dim=1); computed in float32 as torch does.
    const float next_value = next_q.col(j).maxCoeff();
    targets(j) = rewards(j) + (1.0f - dones(j)) * gamma * next_value;
  }
}

double dqn_huber_loss(const Eigen::Ref<const Eigen::MatrixXf>& q,
                      const Eigen::Ref<const Eigen::MatrixXf>& actions,
                      const Eigen::Ref<const Eigen::RowVectorXf>& targets,
                      Eigen::Ref<Eigen::MatrixXf> grad_q, Eigen::Index mean_over) {
  const Eigen::Index n_actions = q.rows();
  const Eigen::Index batch = q.cols();
  if (grad_q.rows() != n_actions || grad_q.cols() != batch || actions.cols() != batch ||
      targets.size() != batch)
    throw std::invalid_argument("dqn_huber_loss: shapes differ");
  grad_q.setZero();
  const Eigen::Index divisor = mean_over > 0 ? mean_over : batch;
  const float inv_divisor = 1.0f / static_cast<float>(divisor);
  double loss = 0.0;
  for (Eigen::Index j = 0; j < batch; ++j) {
    // th.gather(q, dim=1, index=actions.long()): the float action truncates to its index.
    const auto a = static_cast<Eigen::Index>(actions(0, j));
    if (a < 0 || a >= n_actions)
      throw std::out_of_range("dqn_huber_loss: action " + std::to_string(a) + " outside [0, " +
                              std::to_string(n_actions) + ")");
    const float diff = q(a, j) - targets(j);
    const float abs_diff = std::abs(diff);
    // torch smooth_l1_loss, beta = 1: 0.5 d^2 where |d| < 1, else |d| - 0.5; its derivative is d
    // clamped to [-1, 1].
    loss += abs_diff < 1.0f ? 0.5 * static_cast<double>(diff) * diff : abs_diff - 0.5;
    grad_q(a, j) = std::clamp(diff, -1.0f, 1.0f) * inv_divisor;
  }
  return loss / static_cast<double>(divisor);
}

}  // namespace rlrun
