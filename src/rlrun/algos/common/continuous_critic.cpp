#include "rlrun/algos/common/continuous_critic.hpp"

#include "rlrun/algos/common/actor_critic_policy.hpp"
#include "rlrun/algos/common/polyak.hpp"

namespace rlrun {

ContinuousCritic::ContinuousCritic(int input_dim, const std::vector<int>& net_arch,
                                   Activation activation)
    : q_(input_dim, net_arch, 1, activation), target_(q_) {}

void ContinuousCritic::init(Rng& rng) {
  q_.init_torch_default(rng);
  target_.params() = q_.params();
}

void ContinuousCritic::compute_target_values(
    const Eigen::Ref<const Eigen::MatrixXf>& obs_action) {
  target_values_ = target_.forward(obs_action);
}

double ContinuousCritic::loss_and_gradient(const Eigen::Ref<const Eigen::MatrixXf>& obs_action,
                                           const Eigen::Ref<const Eigen::MatrixXf>& y,
                                           float scale) {
  const Eigen::MatrixXf& q = q_.forward(obs_action);
  grad_values_ = q - y;
  const double loss = static_cast<double>(grad_values_.squaredNorm()) * scale;
  // d/dQ_j of scale * sum_j (Q_j - y_j)^2 = 2 scale (Q_j - y_j).
  grad_values_ *= 2.0f * scale;
  q_.zero_grad();
  q_.backward(grad_values_);
  return loss;
}

void ContinuousCritic::compute_values(const Eigen::Ref<const Eigen::MatrixXf>& obs_action) {
  values_ = q_.forward(obs_action);
}

void ContinuousCritic::compute_action_gradient(const Eigen::Ref<const Eigen::MatrixXf>& grad_q,
                                               int action_dim) {
  q_.backward_input(grad_q, action_gradient_, q_.in_dim() - action_dim);
}

void ContinuousCritic::soft_update(float tau) {
  polyak_update(q_.params(), target_.params(), tau);
}

void ContinuousCritic::save(const std::string& online_prefix, const std::string& target_prefix,
                            TensorMap& tensors) const {
  const std::string head = std::to_string(2 * (q_.num_layers() - 1));
  save_mlp(q_, online_prefix, online_prefix + "." + head, tensors);
  save_mlp(target_, target_prefix, target_prefix + "." + head, tensors);
}

void ContinuousCritic::load(const std::string& online_prefix, const std::string& target_prefix,
                            const TensorMap& tensors) {
  const std::string head = std::to_string(2 * (q_.num_layers() - 1));
  load_mlp(q_, online_prefix, online_prefix + "." + head, tensors);
  load_mlp(target_, target_prefix, target_prefix + "." + head, tensors);
}

}  // namespace rlrun
