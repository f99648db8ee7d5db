#include "rlrun/algos/sac/sac_loss.hpp"

#include <algorithm>
#include <stdexcept>

namespace rlrun {

void sac_critic_target(const Eigen::Ref<const Eigen::RowVectorXf>& rewards,
                       const Eigen::Ref<const Eigen::RowVectorXf>& dones,
                       const std::vector<const Eigen::MatrixXf*>& next_q_values,
                       const Eigen::Ref<const Eigen::RowVectorXf>& next_log_prob, float ent_coef,
                       float gamma, Eigen::Ref<Eigen::MatrixXf> target) {
  const Eigen::Index n = rewards.size();
  bool sizes_ok = !next_q_values.empty() && dones.size() == n && next_log_prob.size() == n &&
                  target.rows() == 1 && target.cols() == n;
  for (const Eigen::MatrixXf* q : next_q_values) sizes_ok = sizes_ok && q->cols() == n;
  if (!sizes_ok)
    throw std::invalid_argument(
        "sac_critic_target: critic values, rewards, dones, log_prob and target differ in size");
  for (Eigen::Index j = 0; j < n; ++j) {
    float next_q = (*next_q_values[0])(0, j);
    for (size_t i = 1; i < next_q_values.size(); ++i)
      next_q = std::min(next_q, (*next_q_values[i])(0, j));
    next_q -= ent_coef * next_log_prob(j);
    target(0, j) = rewards(j) + (1.0f - dones(j)) * gamma * next_q;
  }
}

double sac_actor_loss(const std::vector<const Eigen::MatrixXf*>& q_values,
                      const Eigen::Ref<const Eigen::RowVectorXf>& log_prob, float ent_coef,
                      float inv_batch, std::vector<Eigen::MatrixXf>& grad_q,
                      Eigen::RowVectorXf& grad_log_prob) {
  const size_t n_critics = q_values.size();
  if (n_critics == 0 || grad_q.size() != n_critics)
    throw std::invalid_argument("sac_actor_loss: need one gradient matrix per critic");
  const Eigen::Index n = log_prob.size();
  for (Eigen::MatrixXf& g : grad_q) g.setZero(1, n);
  grad_log_prob.setConstant(n, ent_coef * inv_batch);
  double sum = 0.0;
  for (Eigen::Index j = 0; j < n; ++j) {
    size_t arg = 0;
    float min_q = (*q_values[0])(0, j);
    for (size_t i = 1; i < n_critics; ++i) {
      const float q = (*q_values[i])(0, j);
      if (q < min_q) {
        min_q = q;
        arg = i;
      }
    }
    grad_q[arg](0, j) = -inv_batch;
    sum += static_cast<double>(ent_coef * log_prob(j) - min_q);
  }
  return sum * static_cast<double>(inv_batch);
}

}  // namespace rlrun
