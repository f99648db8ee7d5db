#pragma once
// Twin Delayed DDPG (Fujimoto et al. 2018, arXiv:1802.09477) with SB3 2.x semantics, defaults
// and key names (stable_baselines3/td3/td3.py, td3/policies.py, common/policies.py
// ContinuousCritic, common/off_policy_algorithm.py): a deterministic tanh actor, n_critics (2)
// Q-networks on concat(obs, action), clipped double-Q targets with target policy smoothing,
// the actor and all targets updated every policy_delay-th gradient step. Actions live in
// [-1, 1] inside the algorithm (replay buffer, critics, noise) and are rescaled to the Box
// bounds for the env. DDPG (ddpg/ddpg.hpp) is this class with policy_delay 1, no smoothing and
// one critic, as SB3's DDPG is a TD3 subclass with those settings.
//
// One gradient step (train_on_batch, td3.cpp) reads top to bottom like TD3.train's loop body.
// Its networks are SplitMlps, so a training minibatch's parts run on the run's threads
// (AlgorithmSetup::pool, `--threads`), with the same bits on any number.
#include <string>
#include <vector>

#include "rlrun/algos/common/action_noise.hpp"
#include "rlrun/algos/common/activation_config.hpp"
#include "rlrun/algos/common/box_action_selection.hpp"
#include "rlrun/algos/common/continuous_critic.hpp"
#include "rlrun/algos/common/extractor_optimizers.hpp"
#include "rlrun/algos/common/features_extractor_config.hpp"
#include "rlrun/algos/common/net_arch.hpp"
#include "rlrun/algos/common/off_policy.hpp"
#include "rlrun/algos/td3/td3_actor.hpp"
#include "rlrun/core/schedule.hpp"
#include "rlrun/nn/adam.hpp"

namespace rlrun {

// SB3 TD3Policy keyword arguments (policy_kwargs in rl-zoo).
struct Td3PolicyConfig {
  NetArchPiQf net_arch = {{400, 300}, {400, 300}};  // actor (pi), each critic (qf)
  Activation activation_fn = Activation::kReLU;     // SB3 default nn.ReLU
  int n_critics = 2;             // number of Q-networks; targets use their minimum
  bool normalize_images = true;  // SB3: image observations / 255 before the networks
  // SB3 policy_kwargs features_extractor_class (CnnPolicy: NatureCNN), features_extractor_kwargs'
  // features_dim, share_features_extractor (false: actor and critic, and so their targets,
  // have one each).
  FeaturesExtractor features_extractor_class = FeaturesExtractor::kFlatten;
  int features_dim = 512;
  int cnn_output_dim = 256;
  bool share_features_extractor = false;

  FeaturesExtractorSettings extractor() const {
    return {features_extractor_class, features_dim, cnn_output_dim, normalize_images};
  }

  template <class V>
  void visit(V& v) {
    v("net_arch", net_arch, kNetArchPiQfDoc, layer_width());
    v("activation_fn", activation_fn, kActivationFnDoc);
    v("n_critics", n_critics, "number of Q-networks; targets use their minimum", in_range(1, 100));
    v("normalize_images", normalize_images, kNormalizeImagesDoc);
    visit_features_extractor(v, features_extractor_class, features_dim, cnn_output_dim);
    v("share_features_extractor", share_features_extractor, kOffPolicyShareFeaturesExtractorDoc);
  }
};

// What one gradient step computed (TD3.train logs the means over a train() call).
struct Td3StepStats {
  double critic_loss = 0.0;  // sum over critics of mse(Q_i, y)
  double actor_loss = 0.0;   // -mean Q_1(s, mu(s)); only when actor_updated
  bool actor_updated = false;
};

class TD3 : public OffPolicyAlgorithm {
 public:
  struct Config {
    Schedule learning_rate = Schedule::constant(1e-3);
    OffPolicyConfig off_policy;      // SB3 TD3 defaults: 1e6, 100, 256, 0.005, 0.99, 1, 1
    ActionNoiseConfig action_noise;  // none by default (rl-zoo: normal, std 0.1)
    int policy_delay = 2;
    double target_policy_noise = 0.2;
    double target_noise_clip = 0.5;
    Td3PolicyConfig policy;

    template <class V>
    void visit(V& v) {
      v("learning_rate", learning_rate,
        "Adam step size of the actor and the critics: a number or lin_<initial>", non_negative());
      off_policy.visit(v);
      action_noise.visit(v);
      v("policy_delay", policy_delay,
        "update the actor and the targets every N gradient steps (critics every step)",
        at_least(1));
      v("target_policy_noise", target_policy_noise,
        "std of the Gaussian smoothing noise on target actions", non_negative());
      v("target_noise_clip", target_noise_clip, "clip of the target smoothing noise",
        non_negative());
      v("policy", policy, "networks: net_arch, activation_fn, n_critics");
    }
  };

  static constexpr SpaceKind kActionSpaces[] = {SpaceKind::kBox};

  // Problems of `config` with these spaces (registry: checked before anything trains).
  static ConfigProblems check(const Config& config, const AlgorithmSetup& setup);

  // Throws std::invalid_argument for bad settings or spaces (Box observations; bounded Box
  // actions). `id` names the algorithm in logs and model files (DDPG reuses this class).
  TD3(const Config& config, const AlgorithmSetup& setup, std::string id = "TD3");

  // actor(obs) rescaled to the Box bounds; deterministic or not alike (SB3 TD3Policy._predict).
  void export_policy(PolicyGraph& graph, const std::string& obs, bool with_value) const override;
  void predict(const Eigen::Ref<const Eigen::MatrixXf>& obs, bool deterministic,
               Eigen::MatrixXf& actions) override;
  // SB3 TD3Policy.state_dict(): actor.mu.*, actor_target.mu.*, critic.qf<i>.*,
  // critic_target.qf<i>.*, and with CnnPolicy each one's features_extractor.*
  void save(TensorMap& tensors) const override;
  void load(const TensorMap& tensors) override;

  // SB3 OffPolicyAlgorithm._sample_action: warmup = uniform samples of the action space,
  // otherwise actor(obs); exploration noise added and clipped to [-1, 1] in both cases.
  // buffer_actions in [-1, 1], env_actions in [low, high].
  void select_actions(const Eigen::MatrixXf& obs, bool warmup, Eigen::MatrixXf& env_actions,
                      Eigen::MatrixXf& buffer_actions) override;

  // One iteration of TD3.train's loop on `batch` (actions in [-1, 1]) with learning rate lr:
  // n_updates += 1, critic update, and on every policy_delay-th update the actor update and
  // the Polyak updates. Public for tests and benchmarks: the gradients stay in the networks'
  // grads() after the step.
  Td3StepStats train_on_batch(const ReplayBatch& batch, float lr);

  const Config& config() const { return config_; }
  Td3Actor& actor() { return actor_; }
  const Td3Actor& actor() const { return actor_; }
  Td3Actor& actor_target() { return actor_target_; }
  const Td3Actor& actor_target() const { return actor_target_; }
  ContinuousCritic& critic() { return critic_; }
  const ContinuousCritic& critic() const { return critic_; }
  ContinuousCritic& critic_target() { return critic_target_; }
  const ContinuousCritic& critic_target() const { return critic_target_; }
  // From the last train_on_batch: y (1 x batch) and the clipped smoothing noise
  // (action_dim x batch).
  const Eigen::MatrixXf& last_critic_target() const { return target_q_; }
  const Eigen::MatrixXf& last_smoothing_noise() const { return smoothing_noise_; }

 private:
  // `gradient_steps` updates from the replay buffer (SB3 TD3.train), logging the means.
  void train(int gradient_steps, Logger* logger) override;
  void on_episode_end(int env) override { acting_.on_episode_end(env); }

  Config config_;
  int action_dim_ = 0;
  Rng smoothing_rng_;
  Td3Actor actor_, actor_target_;
  ContinuousCritic critic_, critic_target_;
  Adam actor_optimizer_;
  ExtractorOptimizers extractor_optimizers_;  // CnnPolicy: the actor's and the critic's CNN
  // SB3 steps all critics with one Adam over their concatenated parameters; Adam is
  // element-wise with one step count, so one Adam per critic is the same update.
  std::vector<Adam> critic_optimizers_;
  ActingCopy<Td3Actor> acting_actor_{actor_};
  BoxActionSelection acting_;  // warmup samples, exploration noise, scaling to the Box

  // Training workspaces (a gradient step allocates nothing while the batch size is unchanged).
  Eigen::MatrixXf smoothing_noise_, next_actions_, target_q_, grad_q_, grad_actions_;
  // Per critic (they may run on different cores): d critic_loss / d Q_i and its loss.
  std::vector<Eigen::MatrixXf> critic_grad_q_;
  std::vector<double> critic_losses_;
};

}  // namespace rlrun
