#pragma once
// TD3's (and DDPG's) deterministic actor, SB3 td3/policies.py Actor: mu = create_mlp(obs_dim,
// action_dim, net_arch, squash_output=True), i.e. Linear -> act -> ... -> Linear -> Tanh, so
// actions are in [-1, 1]; rescaling to the Box bounds happens outside (SB3's unscale_action).
// The Mlp holds the linear layers (a SplitMlp: a training minibatch runs on both cores); the
// final tanh is applied here.
#include <Eigen/Core>
#include <string>
#include <vector>

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

  int action_dim() const { return net_.net().out_dim(); }
  // The network's parameters and gradients.
  Mlp& net() { return net_.net(); }
  const Mlp& net() const { return net_.net(); }

  // tanh(mu(obs)) -> action_dim x batch. Keeps the forward pass for backward(); the reference
  // stays valid until the next forward.
  const Eigen::MatrixXf& forward(const Eigen::Ref<const Eigen::MatrixXf>& obs);
  const Eigen::MatrixXf& actions() const { return actions_; }

  // Backpropagates dL/d(actions) of the last forward through the tanh into the network:
  // net().grads() becomes the loss's gradient (optimizer.zero_grad(); loss.backward()).
  void backward(const Eigen::Ref<const Eigen::MatrixXf>& grad_actions);

  // SB3 state_dict names: <prefix>.mu.<2l>.weight/bias for layer l (actor.mu.0.weight, ...,
  // actor.mu.4.weight for net_arch [400, 300]).
  void save(const std::string& prefix, TensorMap& tensors) const;
  void load(const std::string& prefix, const TensorMap& tensors);

 private:
  SplitMlp net_;
  Eigen::MatrixXf actions_, grad_pre_tanh_;
};

}  // namespace rlrun
