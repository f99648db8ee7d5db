#include "rlrun/algos/td3/td3_critic.hpp"

#include "rlrun/algos/common/actor_critic_policy.hpp"
#include "rlrun/algos/common/polyak.hpp"

namespace rlrun {

Td3Critic::Td3Critic(int input_dim, const std::vector<int>& net_arch, Activation activation)
    : q_(input_dim, net_arch, 1, activation), target_(q_) {}

void Td3Critic::init(Rng& rng) {
  q_.init_torch_default(rng);
  target_.params() = q_.params();
}

void Td3Critic::compute_target_values(const Eigen::Ref<const Eigen::MatrixXf>& obs_action) {
  target_values_ = target_.forward(obs_action);
}

double Td3Critic::loss_and_gradient(const Eigen::Ref<const Eigen::MatrixXf>& obs_action,
                                    const Eigen::Ref<const Eigen::MatrixXf>& y, float inv_batch) {
  const Eigen::MatrixXf& q = q_.forward(obs_action);
  grad_values_ = q - y;
  const double loss = static_cast<double>(grad_values_.squaredNorm()) * inv_batch;
  // d/dQ_j of sum_j (Q_j - y_j)^2 / batch = 2 (Q_j - y_j) / batch.
  grad_values_ *= 2.0f * inv_batch;
  q_.zero_grad();
  q_.backward(grad_values_);
  return loss;
}

void Td3Critic::compute_values(const Eigen::Ref<const Eigen::MatrixXf>& obs_action) {
  values_ = q_.forward(obs_action);
}

void Td3Critic::compute_action_gradient(const Eigen::Ref<const Eigen::MatrixXf>& grad_q,
                                        int action_dim) {
  q_.backward(grad_q, &grad_input_);
  action_gradient_ = grad_input_.bottomRows(action_dim);
}

void Td3Critic::soft_update(float tau) { polyak_update(q_.params(), target_.params(), tau); }

void Td3Critic::save(const std::string& online_prefix, const std::string& target_prefix,
                     TensorMap& tensors) const {
  const std::string head = std::to_string(2 * (q_.num_layers() - 1));
  save_mlp(q_, online_prefix, online_prefix + "." + head, tensors);
  save_mlp(target_, target_prefix, target_prefix + "." + head, tensors);
}

void Td3Critic::load(const std::string& online_prefix, const std::string& target_prefix,
                     const TensorMap& tensors) {
  const std::string head = std::to_string(2 * (q_.num_layers() - 1));
  load_mlp(q_, online_prefix, online_prefix + "." + head, tensors);
  load_mlp(target_, target_prefix, target_prefix + "." + head, tensors);
}

}  // namespace rlrun
