#pragma once
// CrossQ (Bhatt et al. 2024, "CrossQ: Batch Normalization in Deep Reinforcement Learning for
// Greater Sample Efficiency and Simplicity", ICLR 2024, openreview.net/forum?id=PczQtTsTIX) with
// sb3-contrib 2.4's semantics, defaults and key names (sb3_contrib/crossq/crossq.py,
// crossq/policies.py, common/torch_layers.py BatchRenorm1d; reference implementation sbx).
// SAC without target networks: the actor and the n_critics Q-networks put a BatchRenorm before
// every Linear (crossq_networks.hpp, nn/batch_renorm.hpp), and the critics evaluate (s, a) and
// (s', a') in ONE train-mode forward pass over the concatenated batch, so that the batch
// statistics cover both distributions; the next Q-values of that pass, detached, make the soft
// Bellman target. The actor (and the entropy coefficient) step every policy_delay gradient
// steps. Adam with betas (0.5, 0.999) for the actor and the critics.
//
// One gradient step (train_on_batch, crossq.cpp) reads top to bottom like crossq.py's loop.
#include <Eigen/Core>
#include <string>
#include <vector>

#include "rlrun/algos/common/action_noise.hpp"
#include "rlrun/algos/common/activation_config.hpp"
#include "rlrun/algos/common/box_action_selection.hpp"
#include "rlrun/algos/common/entropy_coefficient.hpp"
#include "rlrun/algos/common/net_arch.hpp"
#include "rlrun/algos/common/off_policy.hpp"
#include "rlrun/algos/crossq/crossq_networks.hpp"
#include "rlrun/core/schedule.hpp"
#include "rlrun/nn/adam.hpp"

namespace rlrun {

// sb3-contrib CrossQPolicy / MlpPolicy keyword arguments (policy_kwargs in rl-zoo).
struct CrossQPolicyConfig {
  // "a wider network significantly improves performance": [1024, 1024] critics.
  NetArchPiQf net_arch = {{256, 256}, {1024, 1024}};
  Activation activation_fn = Activation::kReLU;
  bool batch_norm = true;
  double batch_norm_momentum = 0.01;  // "Jax implementation is 1 - momentum = 0.99"
  double batch_norm_eps = 0.001;
  int64_t renorm_warmup_steps = 100000;
  double log_std_init = -3.0;  // gSDE
  bool use_expln = false;      // gSDE
  double clip_mean = 2.0;      // gSDE
  bool normalize_images = true;
  int n_critics = 2;

  CrossQNorm norm() const;
  SacActorSde actor_sde(bool use_sde) const;

  template <class V>
  void visit(V& v) {
    v("net_arch", net_arch, kNetArchPiQfDoc, layer_width());
    v("activation_fn", activation_fn, kActivationFnDoc);
    v("batch_norm", batch_norm, "a BatchRenorm layer before every Linear of actor and critics");
    v("batch_norm_momentum", batch_norm_momentum,
      "rate of the BatchRenorm running statistics (ra += momentum * (batch - ra))",
      in_range(1e-9, 1));
    v("batch_norm_eps", batch_norm_eps, "added to the BatchRenorm variances", in_range(1e-12, 1));
    v("renorm_warmup_steps", renorm_warmup_steps,
      "train-mode passes of each BatchRenorm as plain batch norm before renormalisation (r_max "
      "3, d_max 5) towards the running statistics",
      non_negative());
    v("log_std_init", log_std_init, "gSDE (use_sde): initial log standard deviation",
      in_range(-20, 20));
    v("use_expln", use_expln, "gSDE (use_sde): expln instead of exp keeps the std positive");
    v("clip_mean", clip_mean, "gSDE (use_sde): clip the mean to [-clip_mean, clip_mean] (0: off)",
      in_range(0, 1e6));
    v("normalize_images", normalize_images, kNormalizeImagesDoc);
    v("n_critics", n_critics, "number of Q-networks; targets use their minimum", in_range(1, 100));
  }
};

// The per-step scalars CrossQ.train records.
struct CrossQStepStats {
  double ent_coef = 0.0;       // alpha used in this step (before its update)
  double critic_loss = 0.0;    // 0.5 * sum over critics of mse
  bool actor_updated = false;  // a policy_delay step
  double actor_loss = 0.0;
  double ent_coef_loss = 0.0;  // 0 when alpha is fixed
};

class CrossQ : public OffPolicyAlgorithm {
 public:
  // sb3-contrib CrossQ.__init__ (tau is fixed at 1.0: no target networks).
  struct Config {
    Schedule learning_rate = Schedule::constant(1e-3);
    OffPolicyConfig off_policy = [] {
      OffPolicyConfig c;
      c.tau = 1.0;
      return c;
    }();
    std::string ent_coef = "auto";
    std::string target_entropy = "auto";
    int policy_delay = 3;
    bool use_sde = false;
    int sde_sample_freq = -1;
    bool use_sde_at_warmup = false;
    ActionNoiseConfig action_noise;  // none by default
    CrossQPolicyConfig policy;

    template <class V>
    void visit(V& v) {
      v("learning_rate", learning_rate,
        "Adam step size of actor, critics and ent_coef: a number or lin_<initial>", non_negative());
      off_policy.visit(v);
      action_noise.visit(v);
      v("ent_coef", ent_coef, "entropy coefficient: auto, auto_<initial> (learned) or a number",
        EntCoefSpec{});
      v("target_entropy", target_entropy,
        "entropy target when ent_coef is learned: auto (-dim A) or a number", TargetEntropySpec{});
      v("policy_delay", policy_delay,
        "update the actor (and ent_coef) every N gradient steps (counted over the whole run)",
        at_least(1));
      v("use_sde", use_sde,
        "generalized State-Dependent Exploration (gSDE) instead of white noise");
      v("sde_sample_freq", sde_sample_freq,
        "gSDE: new noise matrix every N steps (-1: only at the start of each collection)");
      v("use_sde_at_warmup", use_sde_at_warmup,
        "gSDE: act with the policy's noise before learning_starts instead of uniform samples");
      v("policy", policy,
        "networks: net_arch, activation_fn, batch_norm options, n_critics, gSDE options");
    }
  };

  static constexpr SpaceKind kActionSpaces[] = {SpaceKind::kBox};

  // Problems of `config` with these spaces (registry: checked before anything trains).
  static ConfigProblems check(const Config& config, const AlgorithmSetup& setup);

  // Throws std::invalid_argument for bad settings or spaces (bounded Box actions).
  CrossQ(const Config& config, const AlgorithmSetup& setup);

  // tanh(mu) (deterministic) or a sample, rescaled to the Box bounds; eval-mode BatchRenorm.
  void predict(const Eigen::Ref<const Eigen::MatrixXf>& obs, bool deterministic,
               Eigen::MatrixXf& actions) override;
  // sb3-contrib CrossQPolicy.state_dict(): actor.latent_pi.*, actor.mu.*, actor.log_std.*,
  // critic.qf<i>.* (BatchRenorm running statistics and step counts included), and
  // log_ent_coef (learned) or ent_coef_tensor (fixed).
  void save(TensorMap& tensors) const override;
  void load(const TensorMap& tensors) override;
  // The deterministic action; the value is the first critic's Q(s, a) of that action (eval
  // mode, BatchRenorm folded into the dense layers).
  void export_policy(PolicyGraph& graph, const std::string& obs, bool with_value) const override;

  void select_actions(const Eigen::MatrixXf& obs, bool warmup, Eigen::MatrixXf& env_actions,
                      Eigen::MatrixXf& buffer_actions) override;

  // One pass of CrossQ.train's loop on `batch` (actions in [-1, 1]) with learning rate lr;
  // update_actor: a policy_delay step. Public for tests and benchmarks: the gradients stay in
  // the networks after the step.
  CrossQStepStats train_on_batch(const ReplayBatch& batch, float lr, bool update_actor);

  const CrossQActor& actor() const { return actor_; }
  CrossQActor& actor() { return actor_; }
  const CrossQCritic& critic() const { return critic_; }
  CrossQCritic& critic() { return critic_; }
  const EntropyCoefficient& ent_coef() const { return ent_coef_; }
  const Adam& actor_optimizer() const { return actor_optimizer_; }
  const Adam& critic_optimizer(int i) const { return critic_optimizers_[i]; }
  // From the last train_on_batch: the noise of the next actions and of the policy's actions
  // (action_dim x batch; not with gSDE), the next actions and their log-probabilities, and the
  // soft Bellman target (1 x batch).
  const Eigen::MatrixXf& last_next_noise() const { return next_noise_; }
  const Eigen::MatrixXf& last_policy_noise() const { return policy_noise_; }
  const Eigen::MatrixXf& last_next_actions() const { return next_actions_; }
  const Eigen::RowVectorXf& last_next_log_prob() const { return next_log_prob_; }
  const Eigen::MatrixXf& last_critic_target() const { return target_q_; }

 private:
  void train(int gradient_steps, Logger* logger) override;
  void on_episode_end(int env) override { acting_.on_episode_end(env); }
  void before_collect_step(int64_t collected_steps) override;
  void record_rollout_logs(Logger& logger) override;

  // actor.action_log_prob(obs) with the actor's BatchRenorm in train or eval mode, from
  // `noise` (or gSDE's exploration matrix).
  void sample_actions(const Eigen::Ref<const Eigen::MatrixXf>& obs, bool training,
                      const Eigen::MatrixXf& noise, Eigen::MatrixXf& actions,
                      Eigen::RowVectorXf& log_prob);
  // The joint forward, the target and the critics' step; returns critic_loss.
  double update_critics(const ReplayBatch& b, float alpha, float lr);
  // The delayed part: the actor's train-mode sample, the temperature, the actor's step.
  void update_actor_and_temperature(const ReplayBatch& b, float alpha, float lr,
                                    CrossQStepStats& stats);

  const Config config_;
  const int action_dim_;
  Rng train_rng_, predict_rng_;
  CrossQActor actor_;
  CrossQCritic critic_;
  EntropyCoefficient ent_coef_;
  Adam actor_optimizer_;
  // sb3-contrib steps all critics with one Adam; Adam is element-wise with one step count, so
  // one Adam per critic is the same update.
  std::vector<Adam> critic_optimizers_;
  ActingCopy<CrossQActor> acting_actor_{actor_};
  BoxActionSelection acting_;
  // Training workspaces.
  Eigen::MatrixXf next_noise_, policy_noise_, next_actions_, actions_pi_, all_obs_, all_actions_,
      target_q_, grad_actions_;
  Eigen::RowVectorXf next_log_prob_, log_prob_, q_pi_, grad_log_prob_;
  std::vector<Eigen::MatrixXf> grad_q_, grad_min_q_, grad_critic_actions_;
  std::vector<double> critic_losses_;
  // Acting workspaces.
  Eigen::MatrixXf scaled_actions_;
  Eigen::RowVectorXf acting_log_prob_;
};

}  // namespace rlrun
