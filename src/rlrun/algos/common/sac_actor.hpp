#pragma once
// SAC's actor (SB3 sac/policies.py Actor with SquashedDiagGaussianDistribution; CleanRL
// sac_continuous_action.py Actor), also TQC's (sb3-contrib tqc/policies.py Actor is the same
// network, distribution and state_dict names): latent_pi = Linear -> act -> ... (an activation after EVERY
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
//
// With gSDE (SB3 Actor with use_sde) the network ends in mu alone, clipped by
// nn.Hardtanh(-clip_mean, clip_mean) when clip_mean > 0, and log_std is the state-independent
// matrix of a StateDependentNoise on latent_pi (learn_features and squash_output true): the
// exploration noise is a function of the latent features, drawn anew by reset_noise.
//
// The network reads the output of the actor's features extractor (features_extractor_net.hpp):
// the observation itself, or with SB3's CnnPolicy the actor's own NatureCNN, trained by the
// actor loss through both the sample and its log-probability, saved as
// <prefix>.features_extractor.*.
#include <Eigen/Core>
#include <string>
#include <vector>

#include "rlrun/algos/common/features_extractor_net.hpp"
#include "rlrun/core/state_dict.hpp"
#include "rlrun/core/tensor.hpp"
#include "rlrun/nn/split_mlp.hpp"
#include "rlrun/nn/squashed_gaussian.hpp"
#include "rlrun/nn/state_dependent_noise.hpp"
#include "rlrun/rng.hpp"

namespace rlrun {

class PolicyGraph;

// SB3 Actor's gSDE keyword arguments.
struct SacActorSde {
  bool use_sde = false;
  float log_std_init = -3.0f;  // SB3's SAC Actor default
  bool full_std = true;
  bool use_expln = false;
  float clip_mean = 2.0f;  // Hardtanh bound on mu; <= 0: no clipping
};

class SacActor {
 public:
  SacActor() = default;
  // `pool` runs a minibatch's parts (SplitMlp).
  SacActor(int obs_dim, int action_dim, const std::vector<int>& net_arch, Activation activation,
           const SacActorSde& sde = {}, ThreadPool* pool = nullptr);
  // The same behind a features extractor (the network reads extractor.out_dim() features).
  SacActor(FeaturesExtractorNet extractor, int action_dim, const std::vector<int>& net_arch,
           Activation activation, const SacActorSde& sde = {}, ThreadPool* pool = nullptr);

  int action_dim() const { return action_dim_; }
  FeaturesExtractorNet& features_extractor() { return extractor_; }
  const FeaturesExtractorNet& features_extractor() const { return extractor_; }
  // The network's parameters and gradients (with gSDE log_std is in sde(), not here).
  Mlp& net() { return net_.net(); }
  const Mlp& net() const { return net_.net(); }
  // The acting copy's refresh: the extractor's and the network's parameters and gSDE's log_std
  // (same shapes, no allocation); the copy keeps its own exploration matrices.
  void copy_parameters_from(const SacActor& other);

  bool use_sde() const { return sde_options_.use_sde; }
  // Deploying (nn/policy_graph.hpp): mode() as graph nodes, from the network input
  // `features` to the action in [-1, 1]: tanh of the mean (gSDE: of the mean clipped to
  // +-clip_mean).
  std::string export_mode(PolicyGraph& graph, const std::string& features) const;
  // The same from the node of the network's output (`net_output`: [mu; log_std], or mu with
  // gSDE), e.g. of a network that folds more layers in front of this one's (CrossQ).
  std::string export_mode_from_output(PolicyGraph& graph, const std::string& net_output) const;
  const StateDependentNoise& sde() const { return sde_; }
  StateDependentNoise& sde() { return sde_; }
  // SB3 Actor.reset_noise(batch_size): new exploration matrices (gSDE only).
  void reset_noise(Rng& rng, int batch_size);
  // SB3 Actor.get_std().mean() (train/std); gSDE only.
  double mean_std() const { return sde_.mean_std(); }
  // gSDE's exploration matrices for a checkpoint (nothing without gSDE).
  void write_state(StateWriter out) const;
  void read_state(const StateReader& in);

  // SB3 action_log_prob: a reparameterised sample and its log-probability (tanh-corrected),
  // actions resized to action_dim x batch, in (-1, 1). Keeps the forward pass for backward().
  // With gSDE the noise comes from the exploration matrices and rng is not used.
  void sample(const Eigen::Ref<const Eigen::MatrixXf>& obs, Rng& rng, Eigen::MatrixXf& actions,
              Eigen::RowVectorXf& log_prob);
  // The same with given standard-normal noise (action_dim x batch): updates and tests. Not
  // with gSDE (std::logic_error).
  void sample_from_noise(const Eigen::Ref<const Eigen::MatrixXf>& obs,
                         const Eigen::Ref<const Eigen::MatrixXf>& noise, Eigen::MatrixXf& actions,
                         Eigen::RowVectorXf& log_prob);
  // SB3 deterministic=True: tanh(mu) (mu clipped first with gSDE).
  void mode(const Eigen::Ref<const Eigen::MatrixXf>& obs, Eigen::MatrixXf& actions);

  // Backward of a loss L(actions, log_prob) of the last sample, given dL/da (action_dim x batch)
  // and dL/dlog_prob: pathwise through the squashed Gaussian and the log_std clamp into the
  // network: net().grads() becomes the loss's gradient (optimizer.zero_grad(); loss.backward()),
  // and a learned extractor's grads() too. With gSDE, sde().log_std_grad() too, and the
  // gradient also reaches latent_pi through the noise and the variance (learn_features).
  void backward(const Eigen::Ref<const Eigen::MatrixXf>& grad_actions,
                const Eigen::Ref<const Eigen::RowVectorXf>& grad_log_prob);
  // With keep_input_gradient(true), backward() also leaves dL/d(network input) (features x
  // batch, gSDE's latent gradient included when the network has no hidden layer) in
  // input_gradient(): CrossQ's actor puts its batch-renormalised layers in front of heads
  // built as a SacActor without hidden layers.
  void keep_input_gradient(bool keep) { keep_input_gradient_ = keep; }
  const Eigen::MatrixXf& input_gradient() const { return grad_features_; }

  // SB3 state_dict names under `prefix` ("actor"): <prefix>.latent_pi.<2i>.weight/bias,
  // <prefix>.mu.weight/bias, <prefix>.log_std.weight/bias. With gSDE: <prefix>.mu.0.weight/bias
  // (mu is nn.Sequential(Linear, Hardtanh)) or <prefix>.mu.weight/bias without clip_mean, and
  // the <prefix>.log_std matrix. A learned extractor: <prefix>.features_extractor.*.
  void save(const std::string& prefix, TensorMap& tensors) const;
  void load(const std::string& prefix, const TensorMap& tensors);

 private:
  // Runs the network and hands mu and the clamped log_std (or, with gSDE, the clipped mu and
  // the latent features) to the distribution.
  void forward_heads(const Eigen::Ref<const Eigen::MatrixXf>& obs);
  std::string mu_name(const std::string& prefix) const;

  // The network's backward, then the extractor's from the network's input gradient.
  void backward_network(const Eigen::MatrixXf& grad_out, const Eigen::MatrixXf* grad_latent);

  int action_dim_ = 0;
  FeaturesExtractorNet extractor_;
  SplitMlp net_;  // features -> net_arch -> [mu; raw log_std], or mu alone with gSDE
  SquashedGaussian dist_;
  SacActorSde sde_options_;
  StateDependentNoise sde_;
  bool keep_input_gradient_ = false;
  // Workspaces, reused while the batch size stays the same.
  Eigen::MatrixXf log_std_, grad_mean_, grad_log_std_, grad_head_, mu_, grad_latent_,
      grad_features_;
};

}  // namespace rlrun
