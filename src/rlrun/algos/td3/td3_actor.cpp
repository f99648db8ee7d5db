#include "rlrun/algos/td3/td3_actor.hpp"

#include "rlrun/algos/common/actor_critic_policy.hpp"

namespace rlrun {

Td3Actor::Td3Actor(int obs_dim, int action_dim, const std::vector<int>& net_arch,
                   Activation activation, ThreadPool* pool)
    : net_(obs_dim, net_arch, action_dim, activation, pool) {}

const Eigen::MatrixXf& Td3Actor::forward(const Eigen::Ref<const Eigen::MatrixXf>& obs) {
  actions_ = net_.forward(obs).array().tanh().matrix();
  return actions_;
}

void Td3Actor::backward(const Eigen::Ref<const Eigen::MatrixXf>& grad_actions) {
  // d tanh(z) / dz = 1 - tanh(z)^2, read off the stored output.
  grad_pre_tanh_ = (grad_actions.array() * (1.0f - actions_.array().square())).matrix();
  net_.zero_grad_and_backward(grad_pre_tanh_);
}

void Td3Actor::save(const std::string& prefix, TensorMap& tensors) const {
  const std::string tower = prefix + ".mu";
  save_mlp(net(), tower, tower + "." + std::to_string(2 * (net().num_layers() - 1)), tensors);
}

void Td3Actor::load(const std::string& prefix, const TensorMap& tensors) {
  const std::string tower = prefix + ".mu";
  load_mlp(net(), tower, tower + "." + std::to_string(2 * (net().num_layers() - 1)), tensors);
}

}  // namespace rlrun
