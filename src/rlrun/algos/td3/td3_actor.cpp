#include "rlrun/algos/td3/td3_actor.hpp"

#include "rlrun/algos/common/actor_critic_policy.hpp"
#include "rlrun/algos/common/polyak.hpp"

#include <utility>

namespace rlrun {

Td3Actor::Td3Actor(int obs_dim, int action_dim, const std::vector<int>& net_arch,
                   Activation activation, ThreadPool* pool)
    : Td3Actor(FeaturesExtractorNet(obs_dim), action_dim, net_arch, activation, pool) {}

Td3Actor::Td3Actor(FeaturesExtractorNet extractor, int action_dim, const std::vector<int>& net_arch,
                   Activation activation, ThreadPool* pool)
    : extractor_(std::move(extractor)),
      net_(extractor_.out_dim(), net_arch, action_dim, activation, pool) {}

void Td3Actor::copy_parameters_from(const Td3Actor& other) {
  extractor_.copy_parameters_from(other.extractor_);
  net().params() = other.net().params();
}

const Eigen::MatrixXf& Td3Actor::forward(const Eigen::Ref<const Eigen::MatrixXf>& obs) {
  actions_ = net_.forward(extractor_.forward(obs)).array().tanh().matrix();
  return actions_;
}

void Td3Actor::backward(const Eigen::Ref<const Eigen::MatrixXf>& grad_actions) {
  // d tanh(z) / dz = 1 - tanh(z)^2, read off the stored output.
  grad_pre_tanh_ = (grad_actions.array() * (1.0f - actions_.array().square())).matrix();
  if (!extractor_.learned()) {
    net_.zero_grad_and_backward(grad_pre_tanh_);
    return;
  }
  net_.zero_grad_and_backward(grad_pre_tanh_, nullptr, &grad_features_);
  extractor_.zero_grad_and_backward(grad_features_);
}

void Td3Actor::save(const std::string& prefix, TensorMap& tensors) const {
  extractor_.save(prefix + ".features_extractor", tensors);
  const std::string tower = prefix + ".mu";
  save_mlp(net(), tower, tower + "." + std::to_string(2 * (net().num_layers() - 1)), tensors);
}

void Td3Actor::load(const std::string& prefix, const TensorMap& tensors) {
  extractor_.load(prefix + ".features_extractor", tensors);
  const std::string tower = prefix + ".mu";
  load_mlp(net(), tower, tower + "." + std::to_string(2 * (net().num_layers() - 1)), tensors);
}

void polyak_update(const Td3Actor& actor, Td3Actor& target, float tau) {
  polyak_update(actor.features_extractor(), target.features_extractor(), tau);
  polyak_update(actor.net().params(), target.net().params(), tau);
}

}  // namespace rlrun
