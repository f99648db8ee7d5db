#include "rlrun/algos/sac/sac_loss.hpp"

#include <algorithm>
#include <stdexcept>

namespace rlrun {

void sac_critic_target(const Eigen::Ref<const Eigen::RowVectorXf>& rewards,
                       const Eigen::Ref<const Eigen::RowVectorXf>& dones,
                       const std::vector<const Eigen::MatrixXf*>& next_q_values,
                       const Eigen::Ref<const Eigen::RowVectorXf>& next_log_prob, float ent_coef,
                       float gamma, Eigen::MatrixXf& target) {
  if (next_q_values.empty()) throw std::invalid_argument("sac_critic_target: no critics");
  const Eigen::Index batch = rewards.size();
  target.resize(1, batch);
  for (Eigen::Index j = 0; j < batch; ++j) {
    float next_q = (*next_q_values[0])(0, j);
    for (size_t i = 1; i < next_q_values.size(); ++i)
      next_q = std::min(next_q, (*next_q_values[i])(0, j));
    next_q -= ent_coef * next_log_prob(j);
    target(0, j) = rewards(j) + (1.0f - dones(j)) * gamma * next_q;
  }
}

double sac_actor_loss(const std::vector<const Eigen::MatrixXf*>& q_values,
                      const Eigen::Ref<const Eigen::RowVectorXf>& log_prob, float ent_coef,
                      std::vector<Eigen::MatrixXf>& grad_q, Eigen::RowVectorXf& grad_log_prob) {
  const size_t n_critics = q_values.size();
  if (n_critics == 0 || grad_q.size() != n_critics)
    throw std::invalid_argument("sac_actor_loss: need one gradient matrix per critic");
  const Eigen::Index batch = log_prob.size();
  const float inv_batch = 1.0f / static_cast<float>(batch);
  for (Eigen::MatrixXf& g : grad_q) g.setZero(1, batch);
  grad_log_prob.setConstant(batch, ent_coef * inv_batch);
  double sum = 0.0;
  for (Eigen::Index j = 0; j < batch; ++j) {
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
  return sum / static_cast<double>(batch);
}

}  // namespace rlrun
