#pragma once
// TD3's (and DDPG's) deterministic actor, SB3 td3/policies.py Actor: mu = create_mlp(obs_dim,
// action_dim, net_arch, squash_output=True), i.e. Linear -> act -> ... -> Linear -> Tanh, so
// actions are in [-1, 1]; rescaling to the Box bounds happens outside (SB3's unscale_action).
// The Mlp holds the linear layers (a SplitMlp: a training minibatch runs on both cores); the
// final tanh is applied here. The network reads the actor's features extractor's output
// (features_extractor_net.hpp): the observation, or with SB3's CnnPolicy the actor's own
// NatureCNN (actor_target has its copy), trained by the actor loss.
#include <Eigen/Core>
#include <string>
#include <vector>

#include "rlrun/algos/common/features_extractor_net.hpp"
#include "rlrun/core/tensor.hpp"
#include "rlrun/nn/split_mlp.hpp"
#include "rlrun/rng.hpp"

namespace rlrun {

class Td3Actor {
 public:
  Td3Actor() = default;
  // Parameters start at zero; call net().init_torch_default(rng) (SB3: torch's Linear init).
  // `pool` runs a minibatch's parts (SplitMlp).
  Td3Actor(int obs_dim, int action_dim, const std::vector<int>& net_arch, Activation activation,
           ThreadPool* pool = nullptr);
  // The same behind a features extractor (the network reads extractor.out_dim() features).
  Td3Actor(FeaturesExtractorNet extractor, int action_dim, const std::vector<int>& net_arch,
           Activation activation, ThreadPool* pool = nullptr);

  int action_dim() const { return net_.net().out_dim(); }
  FeaturesExtractorNet& features_extractor() { return extractor_; }
  const FeaturesExtractorNet& features_extractor() const { return extractor_; }
  // The acting copy's refresh: the extractor's and the network's parameters.
  void copy_parameters_from(const Td3Actor& other);
  // The network's parameters and gradients.
  Mlp& net() { return net_.net(); }
  const Mlp& net() const { return net_.net(); }

  // tanh(mu(obs)) -> action_dim x batch. Keeps the forward pass for backward(); the reference
  // stays valid until the next forward.
  const Eigen::MatrixXf& forward(const Eigen::Ref<const Eigen::MatrixXf>& obs);
  const Eigen::MatrixXf& actions() const { return actions_; }

  // Backpropagates dL/d(actions) of the last forward through the tanh into the network:
  // net().grads() becomes the loss's gradient (optimizer.zero_grad(); loss.backward()), and a
  // learned extractor's grads() too.
  void backward(const Eigen::Ref<const Eigen::MatrixXf>& grad_actions);

  // SB3 state_dict names: <prefix>.mu.<2l>.weight/bias for layer l (actor.mu.0.weight, ...,
  // actor.mu.4.weight for net_arch [400, 300]), and <prefix>.features_extractor.* for a learned
  // extractor.
  void save(const std::string& prefix, TensorMap& tensors) const;
  void load(const std::string& prefix, const TensorMap& tensors);

 private:
  FeaturesExtractorNet extractor_;
  SplitMlp net_;
  Eigen::MatrixXf actions_, grad_pre_tanh_, grad_features_;
};

// polyak_update(actor.parameters(), actor_target.parameters(), tau), the extractor's too.
void polyak_update(const Td3Actor& actor, Td3Actor& target, float tau);

}  // namespace rlrun
