#pragma once
// SAC's actor (SB3 sac/policies.py Actor with SquashedDiagGaussianDistribution; CleanRL
// sac_continuous_action.py Actor): latent_pi = Linear -> act -> ... (an activation after EVERY
// hidden layer), then two linear heads mu and log_std, log_std clamped to [-20, 2], actions
// a = tanh(mu + std * eps) in (-1, 1). Rescaling to the Box bounds happens outside (SB3's
// unscale_action), so the replay buffer and the critics see actions in [-1, 1].
//
// Both heads read the same latent features and get the same torch default init (fan_in =
// last hidden width), so they are stored as ONE linear output layer of 2 * action_dim units on
// top of the hidden layers: rows [0, A) are mu, rows [A, 2A) the raw log_std. That is exactly an
// Mlp (its last layer is linear), and one product instead of two thin ones. save() splits the
// layer back into SB3's actor.mu / actor.log_std tensors. The network is a SplitMlp: a training
// minibatch runs on both cores.
#include <Eigen/Core>
#include <string>
#include <vector>

#include "rlrun/rng.hpp"
#include "rlrun/core/tensor.hpp"
#include "rlrun/nn/split_mlp.hpp"
#include "rlrun/nn/squashed_gaussian.hpp"

namespace rlrun {

class SacActor {
 public:
  SacActor() = default;
  SacActor(int obs_dim, int action_dim, const std::vector<int>& net_arch, Activation activation);

  int obs_dim() const { return net_.net().in_dim(); }
  int action_dim() const { return action_dim_; }
  // The network's parameters and gradients.
  Mlp& net() { return net_.net(); }
  const Mlp& net() const { return net_.net(); }

  // SB3 action_log_prob: a reparameterised sample and its log-probability (tanh-corrected),
  // actions resized to action_dim x batch, in (-1, 1). Keeps the forward pass for backward().
  void sample(const Eigen::Ref<const Eigen::MatrixXf>& obs, Rng& rng, Eigen::MatrixXf& actions,
              Eigen::RowVectorXf& log_prob);
  // The same with given standard-normal noise (action_dim x batch): updates and tests.
  void sample_from_noise(const Eigen::Ref<const Eigen::MatrixXf>& obs,
                         const Eigen::Ref<const Eigen::MatrixXf>& noise, Eigen::MatrixXf& actions,
                         Eigen::RowVectorXf& log_prob);
  // SB3 deterministic=True: tanh(mu).
  void mode(const Eigen::Ref<const Eigen::MatrixXf>& obs, Eigen::MatrixXf& actions);

  // Backward of a loss L(actions, log_prob) of the last sample, given dL/da (action_dim x batch)
  // and dL/dlog_prob: pathwise through the squashed Gaussian and the log_std clamp into the
  // network: net().grads() becomes the loss's gradient (optimizer.zero_grad(); loss.backward()).
  void backward(const Eigen::Ref<const Eigen::MatrixXf>& grad_actions,
                const Eigen::Ref<const Eigen::RowVectorXf>& grad_log_prob);

  // SB3 state_dict names under `prefix` ("actor"): <prefix>.latent_pi.<2i>.weight/bias,
  // <prefix>.mu.weight/bias, <prefix>.log_std.weight/bias.
  void save(const std::string& prefix, TensorMap& tensors) const;
  void load(const std::string& prefix, const TensorMap& tensors);

 private:
  // Runs the network and hands mu and the clamped log_std to the distribution.
  void forward_heads(const Eigen::Ref<const Eigen::MatrixXf>& obs);

  int action_dim_ = 0;
  SplitMlp net_;  // obs -> net_arch -> [mu; raw log_std]
  SquashedGaussian dist_;
  // Workspaces, reused while the batch size stays the same.
  Eigen::MatrixXf log_std_, grad_mean_, grad_log_std_, grad_head_;
};

}  // namespace rlrun
