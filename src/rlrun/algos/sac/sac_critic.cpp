#include "rlrun/algos/sac/sac_critic.hpp"

#include "rlrun/algos/common/actor_critic_policy.hpp"
#include "rlrun/algos/common/polyak.hpp"

namespace rlrun {

SacCritic::SacCritic(int input_dim, const std::vector<int>& net_arch, Activation activation,
                     Rng& rng, AdamConfig adam)
    : q_(input_dim, net_arch, 1, activation) {
  q_.init_torch_default(rng);
  target_ = q_;
  adam_ = Adam({q_.block()}, adam);
}

void SacCritic::compute_target_values(const Eigen::Ref<const Eigen::MatrixXf>& obs_action) {
  target_values_ = target_.forward(obs_action);
}

double SacCritic::loss_and_gradient(const Eigen::Ref<const Eigen::MatrixXf>& obs_action,
                                    const Eigen::Ref<const Eigen::MatrixXf>& y) {
  const Eigen::MatrixXf& q = q_.forward(obs_action);
  const auto batch = static_cast<float>(q.cols());
  grad_values_ = q - y;
  const double loss = 0.5 * static_cast<double>(grad_values_.squaredNorm()) / batch;
  // d/dQ_j of 0.5 * mean_j (Q_j - y_j)^2 = (Q_j - y_j) / batch.
  grad_values_ *= 1.0f / batch;
  q_.zero_grad();
  q_.backward(grad_values_);
  return loss;
}

void SacCritic::compute_values(const Eigen::Ref<const Eigen::MatrixXf>& obs_action) {
  values_ = q_.forward(obs_action);
}

void SacCritic::compute_action_gradient(const Eigen::Ref<const Eigen::MatrixXf>& grad_q,
                                        int action_dim) {
  q_.backward(grad_q, &grad_input_);
  action_gradient_ = grad_input_.bottomRows(action_dim);
}

void SacCritic::soft_update(float tau) { polyak_update(q_.params(), target_.params(), tau); }

void SacCritic::save(const std::string& online_prefix, const std::string& target_prefix,
                     TensorMap& tensors) const {
  const std::string head = std::to_string(2 * (q_.num_layers() - 1));
  save_mlp(q_, online_prefix, online_prefix + "." + head, tensors);
  save_mlp(target_, target_prefix, target_prefix + "." + head, tensors);
}

void SacCritic::load(const std::string& online_prefix, const std::string& target_prefix,
                     const TensorMap& tensors) {
  const std::string head = std::to_string(2 * (q_.num_layers() - 1));
  load_mlp(q_, online_prefix, online_prefix + "." + head, tensors);
  load_mlp(target_, target_prefix, target_prefix + "." + head, tensors);
}

}  // namespace rlrun
