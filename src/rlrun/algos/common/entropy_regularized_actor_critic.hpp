#pragma once
// What SAC (Haarnoja et al. 2018, arXiv:1801.01290 and arXiv:1812.05905; SB3 sac/) and TQC
// (Kuznetsov et al. 2020, arXiv:2005.04269; sb3-contrib tqc/) share: the maximum-entropy
// actor-critic around their critics. A tanh-squashed Gaussian actor (SacActor, with gSDE as an
// option) and its acting copy; n_critics networks on concat(obs, action) with Polyak-averaged
// targets (ContinuousCritic: one output per network for SAC, n_quantiles for TQC); an entropy
// coefficient alpha, fixed or learned towards target_entropy; acting in a Box (warm-up samples,
// exploration noise, rescaling to the bounds); and the pieces of one gradient step that do not
// depend on the critics' form: the reparameterised samples, the actor's loss and step, the
// temperature step and the target update. Actions live in [-1, 1] inside the algorithm
// (replay buffer, critics, noise) and are rescaled to the Box bounds for the env.
//
// Each algorithm's train_on_batch (sac.cpp, tqc.cpp) reads top to bottom like its paper's
// gradient step and calls these pieces in that order; its target and critic loss are its own.
// Its networks are SplitMlps, so a training minibatch's parts run on the run's threads
// (AlgorithmSetup::pool, `--threads`), with the same bits on any number.
#include <Eigen/Core>
#include <string>
#include <vector>

#include "rlrun/algos/common/action_noise.hpp"
#include "rlrun/algos/common/activation_config.hpp"
#include "rlrun/algos/common/box_action_selection.hpp"
#include "rlrun/algos/common/continuous_critic.hpp"
#include "rlrun/algos/common/entropy_coefficient.hpp"
#include "rlrun/algos/common/extractor_optimizers.hpp"
#include "rlrun/algos/common/features_extractor_config.hpp"
#include "rlrun/algos/common/net_arch.hpp"
#include "rlrun/algos/common/off_policy.hpp"
#include "rlrun/algos/common/sac_actor.hpp"
#include "rlrun/core/schedule.hpp"
#include "rlrun/nn/adam.hpp"

namespace rlrun {

// SB3 SACPolicy and sb3-contrib TQCPolicy keyword arguments (policy_kwargs in rl-zoo) but TQC's
// n_quantiles. visit_fields lists them in SB3's order with the algorithm's critic fields
// (`critics(v)`: n_critics, and n_quantiles for TQC) after the activation.
struct EntropyRegularizedPolicyConfig {
  NetArchPiQf net_arch = {{256, 256}, {256, 256}};  // actor (pi), each critic (qf)
  Activation activation_fn = Activation::kReLU;     // SB3 default nn.ReLU
  int n_critics = 2;                                // critic networks
  double log_std_init = -3.0;    // gSDE: initial log std (SB3's SAC Actor default)
  bool full_std = true;          // gSDE: a std per (latent feature, action)
  bool use_expln = false;        // gSDE: expln instead of exp for the std
  double clip_mean = 2.0;        // gSDE: Hardtanh bound on the mean (0 = none)
  bool normalize_images = true;  // SB3: image observations / 255 before the networks
  // SB3 policy_kwargs features_extractor_class (CnnPolicy: NatureCNN), features_extractor_kwargs'
  // features_dim, share_features_extractor (false: the actor and the critic have one each).
  FeaturesExtractor features_extractor_class = FeaturesExtractor::kFlatten;
  int features_dim = 512;
  int cnn_output_dim = 256;
  bool share_features_extractor = false;

  // The actor's gSDE options (SB3 Actor keyword arguments).
  SacActorSde actor_sde(bool use_sde) const;
  FeaturesExtractorSettings extractor() const {
    return {features_extractor_class, features_dim, cnn_output_dim, normalize_images};
  }

 protected:
  template <class V, class Critics>
  void visit_fields(V& v, Critics&& critics) {
    v("net_arch", net_arch, kNetArchPiQfDoc, layer_width());
    v("activation_fn", activation_fn, kActivationFnDoc);
    critics(v);
    v("log_std_init", log_std_init, "gSDE (use_sde): initial log standard deviation",
      in_range(-20, 20));
    v("full_std", full_std,
      "gSDE (use_sde): log_std per latent feature and action (true) or per feature (false)");
    v("use_expln", use_expln, "gSDE (use_sde): expln instead of exp keeps the std positive");
    v("clip_mean", clip_mean, "gSDE (use_sde): clip the mean to [-clip_mean, clip_mean] (0: off)",
      in_range(0, 1e6));
    v("normalize_images", normalize_images, kNormalizeImagesDoc);
    visit_features_extractor(v, features_extractor_class, features_dim, cnn_output_dim);
    v("share_features_extractor", share_features_extractor, kOffPolicyShareFeaturesExtractorDoc);
  }
};

// SB3 SAC.__init__ and sb3-contrib TQC.__init__ arguments they share, with their (equal)
// defaults; off_policy holds SB3's OffPolicyAlgorithm ones (1e6, 100, 256, 0.005, 0.99, 1, 1).
// visit_fields lists them in SB3's order with the algorithm's own (`extra(v)`: TQC's
// top_quantiles_to_drop_per_net) after target_entropy.
struct EntropyRegularizedConfig {
  Schedule learning_rate = Schedule::constant(3e-4);
  OffPolicyConfig off_policy;
  std::string ent_coef = "auto";
  int target_update_interval = 1;
  std::string target_entropy = "auto";
  bool use_sde = false;
  int sde_sample_freq = -1;
  bool use_sde_at_warmup = false;
  ActionNoiseConfig action_noise;  // none by default

 protected:
  template <class V, class Extra>
  void visit_fields(V& v, Extra&& extra) {
    v("learning_rate", learning_rate,
      "Adam step size of actor, critics and ent_coef: a number or lin_<initial>", non_negative());
    off_policy.visit(v);
    action_noise.visit(v);
    v("ent_coef", ent_coef, "entropy coefficient: auto, auto_<initial> (learned) or a number",
      EntCoefSpec{});
    v("target_update_interval", target_update_interval,
      "soft-update the target critics every N gradient steps of a train() call", at_least(1));
    v("target_entropy", target_entropy,
      "entropy target when ent_coef is learned: auto (-dim A) or a number", TargetEntropySpec{});
    extra(v);
    v("use_sde", use_sde, "generalized State-Dependent Exploration (gSDE) instead of white noise");
    v("sde_sample_freq", sde_sample_freq,
      "gSDE: new noise matrix every N steps (-1: only at the start of each collection)");
    v("use_sde_at_warmup", use_sde_at_warmup,
      "gSDE: act with the policy's noise before learning_starts instead of uniform samples");
  }
};

// The per-step scalars SAC.train and TQC.train record (means over a train() call are logged).
struct EntropyRegularizedStepStats {
  double ent_coef = 0.0;       // alpha used in this step (before its update)
  double ent_coef_loss = 0.0;  // 0 when alpha is fixed
  double actor_loss = 0.0;
  double critic_loss = 0.0;  // SAC: 0.5 * sum over critics of mse; TQC: quantile Huber loss
};

class EntropyRegularizedActorCritic : public OffPolicyAlgorithm {
 public:
  // tanh(mu) (deterministic) or a sample, rescaled to the Box bounds.
  void predict(const Eigen::Ref<const Eigen::MatrixXf>& obs, bool deterministic,
               Eigen::MatrixXf& actions) final;
  // SB3 SACPolicy.state_dict() (TQCPolicy's has the same names): actor.*, critic.qf<i>.*,
  // critic_target.qf<i>.*, and log_ent_coef (learned) or ent_coef_tensor (fixed).
  void save(TensorMap& tensors) const final;
  void load(const TensorMap& tensors) final;

  // SB3 OffPolicyAlgorithm._sample_action: warmup = uniform samples of the action space
  // (unless gSDE acts at warmup), otherwise a stochastic actor sample; exploration noise added
  // and clipped to [-1, 1]. buffer_actions in [-1, 1], env_actions in [low, high].
  void select_actions(const Eigen::MatrixXf& obs, bool warmup, Eigen::MatrixXf& env_actions,
                      Eigen::MatrixXf& buffer_actions) final;

  // One gradient step of the algorithm's train() on `batch` (actions in [-1, 1]) with learning
  // rate lr; update_target applies the Polyak update afterwards. Public for tests and
  // benchmarks: the gradients stay in the networks' grads() after the step.
  virtual EntropyRegularizedStepStats train_on_batch(const ReplayBatch& batch, float lr,
                                                     bool update_target) = 0;

  const SacActor& actor() const { return actor_; }
  SacActor& actor() { return actor_; }
  const ContinuousCritic& critic() const { return critic_; }
  ContinuousCritic& critic() { return critic_; }
  const ContinuousCritic& critic_target() const { return critic_target_; }
  ContinuousCritic& critic_target() { return critic_target_; }
  const EntropyCoefficient& ent_coef() const { return ent_coef_; }
  // From the last train_on_batch: the standard normal noise used for the next actions and for
  // the policy's actions (action_dim x batch; not with gSDE).
  const Eigen::MatrixXf& last_next_noise() const { return next_noise_; }
  const Eigen::MatrixXf& last_policy_noise() const { return policy_noise_; }
  // gSDE: the acting actor's exploration matrices (what collection and predict() use).
  const StateDependentNoise& acting_noise() { return acting_actor_.get().sde(); }

 protected:
  // `config` and `policy` as the algorithm's constructor validated them; `critic_outputs`: 1
  // (a Q-value per critic, SAC) or n_quantiles (TQC).
  EntropyRegularizedActorCritic(const std::string& id, const EntropyRegularizedConfig& config,
                                const EntropyRegularizedPolicyConfig& policy,
                                const AlgorithmSetup& setup, int critic_outputs);

  // predict(deterministic) as graph nodes: sets the graph's action and returns the encoded
  // observation and the action in [-1, 1] (`scaled`) for the algorithm's value.
  struct ExportedAction {
    std::string encoded, scaled;
  };
  // The critics' input for that action: cat(critic features, action) as graph nodes.
  std::string export_critic_input(PolicyGraph& graph, const ExportedAction& action) const;
  ExportedAction export_action(PolicyGraph& graph, const std::string& obs) const;

  // ---- the shared pieces of one gradient step, in the order train_on_batch calls them ----
  // The step's reparameterisation noise for `n` samples in SB3's order (for the actions at s,
  // then at s'), or with gSDE one new exploration matrix for the whole batch ("we need to
  // sample because `log_std` may have changed between two gradient steps"). Returns alpha as
  // it is before this step's update (SB3: ent_coef = exp(log_ent_coef.detach())).
  float begin_step(Eigen::Index n);
  // next_actions_, next_log_prob_ = actor.action_log_prob(next_obs) (no gradient is taken).
  void sample_next_actions(const Eigen::Ref<const Eigen::MatrixXf>& next_obs);
  // actions_pi_, log_prob_ = actor.action_log_prob(obs), kept for the actor's backward.
  void sample_policy_actions(const Eigen::Ref<const Eigen::MatrixXf>& obs);
  // actor_loss = (alpha * log_prob - q_pi).mean(), q_pi = Q(s, actions_pi) as the algorithm
  // reads its critics; grad_actions = d actor_loss / d actions_pi through them. Backward
  // pathwise through the squashed Gaussian, one Adam step. Returns the loss.
  double update_actor(const Eigen::RowVectorXf& q_pi, const Eigen::MatrixXf& grad_actions,
                      float alpha, float lr);
  // After the critics' backward and steps (ContinuousCritic::zero_grad_and_backward): the
  // critic's NatureCNN learns from their summed loss, one Adam step with the same lr (SB3's one
  // critic optimizer holds its parameters too). Nothing without a CNN.
  void update_critic_features_extractor(float lr);
  // polyak_update(critic.parameters(), critic_target.parameters(), tau).
  void update_target_critics();

  const EntropyRegularizedConfig config_;
  const int action_dim_;
  ContinuousCritic critic_, critic_target_;
  // SB3 steps all critics with one Adam over their concatenated parameters; Adam is
  // element-wise with one step count, so one Adam per critic is the same update.
  std::vector<Adam> critic_optimizers_;
  EntropyCoefficient ent_coef_;
  // Training workspaces (one gradient step allocates nothing while the batch size is
  // unchanged): the actions at s' and their log-probabilities, the policy's actions at s and
  // theirs, and what the algorithm hands update_actor.
  Eigen::MatrixXf next_actions_, actions_pi_, grad_actions_;
  Eigen::RowVectorXf next_log_prob_, log_prob_, q_pi_;

 private:
  // `gradient_steps` calls of train_on_batch — the target update when `gradient_step %
  // target_update_interval == 0`, counted within this call — then n_updates and the means on
  // `logger`, as SB3's train() records them.
  void train(int gradient_steps, Logger* logger) final;
  void on_episode_end(int env) final { acting_.on_episode_end(env); }
  // gSDE: SB3 collect_rollouts' reset_noise(n_envs) at the start and every sde_sample_freq steps.
  void before_collect_step(int64_t collected_steps) final;
  // gSDE: train/std = actor.get_std().mean().
  void record_rollout_logs(Logger& logger) final;
  // actor.action_log_prob(obs): from `noise` (standard normal, action_dim x n), or with gSDE
  // from the exploration matrices.
  void sample_actions(const Eigen::Ref<const Eigen::MatrixXf>& obs, const Eigen::MatrixXf& noise,
                      Eigen::MatrixXf& actions, Eigen::RowVectorXf& log_prob);

  Rng train_rng_, predict_rng_;
  SacActor actor_;
  Adam actor_optimizer_;
  ExtractorOptimizers extractor_optimizers_;  // CnnPolicy: the actor's and the critic's CNN
  ActingCopy<SacActor> acting_actor_{actor_};
  BoxActionSelection acting_;  // warmup samples, exploration noise, scaling to the Box
  Eigen::MatrixXf policy_noise_, next_noise_;
  Eigen::RowVectorXf grad_log_prob_;
  // Acting workspaces.
  Eigen::MatrixXf scaled_actions_;
  Eigen::RowVectorXf acting_log_prob_;
};

}  // namespace rlrun
