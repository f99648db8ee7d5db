#pragma once
// Soft Actor-Critic (Haarnoja et al. 2018, arXiv:1801.01290 and arXiv:1812.05905) with SB3 2.x
// semantics, defaults and key names (stable_baselines3/sac/sac.py, sac/policies.py,
// common/off_policy_algorithm.py; CleanRL's sac_continuous_action.py is the same update in
// one file): a tanh-squashed Gaussian actor, n_critics (2) Q-networks on concat(obs, action)
// with Polyak-averaged targets, clipped double-Q soft Bellman targets, and an entropy
// coefficient that is fixed or learned towards target_entropy. Actions live in [-1, 1] inside
// the algorithm (replay buffer, critics, noise) and are rescaled to the Box bounds for the env.
//
// One gradient step (train_on_batch, sac.cpp) reads top to bottom like SAC.train's loop body.
// Its networks are SplitMlps, so a training minibatch runs on both cores when ForkJoin's worker
// is on (RLRUN_THREADS=2), with the same bits as on one.
#include <string>
#include <vector>

#include "rlrun/algos/common/action_noise.hpp"
#include "rlrun/algos/common/activation_config.hpp"
#include "rlrun/algos/common/box_action_selection.hpp"
#include "rlrun/algos/common/continuous_critic.hpp"
#include "rlrun/algos/common/entropy_coefficient.hpp"
#include "rlrun/algos/common/entropy_regularized_train.hpp"
#include "rlrun/algos/common/net_arch.hpp"
#include "rlrun/algos/common/off_policy.hpp"
#include "rlrun/algos/common/sac_actor.hpp"
#include "rlrun/core/schedule.hpp"
#include "rlrun/nn/adam.hpp"

namespace rlrun {

// SB3 SACPolicy / MlpPolicy keyword arguments (policy_kwargs in rl-zoo).
struct SacPolicyConfig {
  NetArchPiQf net_arch = {{256, 256}, {256, 256}};  // actor (pi), each critic (qf)
  Activation activation_fn = Activation::kReLU;          // SB3 default nn.ReLU
  int n_critics = 2;                       // number of Q-networks (clipped double-Q: 2)
  double log_std_init = -3.0;              // gSDE: initial log std (SB3's SAC Actor default)
  bool full_std = true;                    // gSDE: a std per (latent feature, action)
  bool use_expln = false;                  // gSDE: expln instead of exp for the std
  double clip_mean = 2.0;                  // gSDE: Hardtanh bound on the mean (0 = none)

  template <class V>
  void visit(V& v) {
    v("net_arch", net_arch, kNetArchPiQfDoc, layer_width());
    v("activation_fn", activation_fn, kActivationFnDoc);
    v("n_critics", n_critics, "number of Q-networks; targets use their minimum", in_range(1, 100));
    v("log_std_init", log_std_init, "gSDE (use_sde): initial log standard deviation",
      in_range(-20, 20));
    v("full_std", full_std,
      "gSDE (use_sde): log_std per latent feature and action (true) or per feature (false)");
    v("use_expln", use_expln, "gSDE (use_sde): expln instead of exp keeps the std positive");
    v("clip_mean", clip_mean, "gSDE (use_sde): clip the mean to [-clip_mean, clip_mean] (0: off)",
      in_range(0, 1e6));
  }
};

class SAC : public OffPolicyAlgorithm {
 public:
  struct Config {
    Schedule learning_rate = Schedule::constant(3e-4);
    OffPolicyConfig off_policy;  // SB3 SAC defaults: 1e6, 100, 256, 0.005, 0.99, 1, 1
    std::string ent_coef = "auto";
    int target_update_interval = 1;
    std::string target_entropy = "auto";
    bool use_sde = false;
    int sde_sample_freq = -1;
    bool use_sde_at_warmup = false;
    SacPolicyConfig policy;
    ActionNoiseConfig action_noise;  // none by default

    template <class V>
    void visit(V& v) {
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
      v("use_sde", use_sde, "generalized State-Dependent Exploration (gSDE) instead of white noise");
      v("sde_sample_freq", sde_sample_freq,
        "gSDE: new noise matrix every N steps (-1: only at the start of each collection)");
      v("use_sde_at_warmup", use_sde_at_warmup,
        "gSDE: act with the policy's noise before learning_starts instead of uniform samples");
      v("policy", policy, "networks: net_arch, activation_fn, n_critics, gSDE options");
    }
  };

  static constexpr SpaceKind kActionSpaces[] = {SpaceKind::kBox};

  // Problems of `config` with these spaces (registry: checked before anything trains).
  static ConfigProblems check(const Config& config, const AlgorithmSetup& setup);

  // Throws std::invalid_argument for bad settings or spaces (Box observations; bounded Box
  // actions).
  SAC(const Config& config, const AlgorithmSetup& setup);

  // tanh(mu) (deterministic) or a sample, rescaled to the Box bounds.
  void export_policy(PolicyGraph& graph, const std::string& obs, bool with_value) const override;
  void predict(const Eigen::Ref<const Eigen::MatrixXf>& obs, bool deterministic,
               Eigen::MatrixXf& actions) override;
  // SB3 SACPolicy.state_dict(): actor.*, critic.qf<i>.*, critic_target.qf<i>.*, and
  // log_ent_coef (learned) or ent_coef_tensor (fixed).
  void save(TensorMap& tensors) const override;
  void load(const TensorMap& tensors) override;

  // SB3 OffPolicyAlgorithm._sample_action: warmup = uniform samples of the action space,
  // otherwise a stochastic actor sample; exploration noise added and clipped to [-1, 1].
  // buffer_actions in [-1, 1], env_actions in [low, high].
  void select_actions(const Eigen::MatrixXf& obs, bool warmup, Eigen::MatrixXf& env_actions,
                      Eigen::MatrixXf& buffer_actions) override;

  // One gradient step of SAC.train on `batch` (actions in [-1, 1]) with learning rate lr;
  // update_target applies the Polyak update afterwards. Public for tests and benchmarks: the
  // gradients stay in the networks' grads() after the step.
  EntropyRegularizedStepStats train_on_batch(const ReplayBatch& batch, float lr, bool update_target);

  const Config& config() const { return config_; }
  const SacActor& actor() const { return actor_; }
  SacActor& actor() { return actor_; }
  const ContinuousCritic& critic() const { return critic_; }
  ContinuousCritic& critic() { return critic_; }
  const ContinuousCritic& critic_target() const { return critic_target_; }
  ContinuousCritic& critic_target() { return critic_target_; }
  const EntropyCoefficient& ent_coef() const { return ent_coef_; }
  // From the last train_on_batch: the soft Bellman target y (1 x batch) and the standard
  // normal noise used for the next actions and for the policy's actions (action_dim x batch).
  const Eigen::MatrixXf& last_critic_target() const { return target_q_; }
  const Eigen::MatrixXf& last_next_noise() const { return next_noise_; }
  const Eigen::MatrixXf& last_policy_noise() const { return policy_noise_; }
  // gSDE: the acting actor's exploration matrices (what collection and predict() use).
  const StateDependentNoise& acting_noise() { return acting_actor_.get().sde(); }

 private:
  // `gradient_steps` updates from the replay buffer (SB3 SAC.train), logging the means.
  void train(int gradient_steps, Logger* logger) override;
  void on_episode_end(int env) override { acting_.on_episode_end(env); }
  // gSDE: SB3 collect_rollouts' reset_noise(n_envs) at the start and every sde_sample_freq steps.
  void before_collect_step(int64_t collected_steps) override;
  // gSDE: train/std = actor.get_std().mean().
  void record_rollout_logs(Logger& logger) override;

  Config config_;
  int action_dim_ = 0;
  Rng train_rng_, predict_rng_;
  SacActor actor_;
  ContinuousCritic critic_, critic_target_;
  Adam actor_optimizer_;
  // SB3 steps all critics with one Adam over their concatenated parameters; Adam is
  // element-wise with one step count, so one Adam per critic is the same update.
  std::vector<Adam> critic_optimizers_;
  EntropyCoefficient ent_coef_;
  ActingCopy<SacActor> acting_actor_{actor_};
  BoxActionSelection acting_;  // warmup samples, exploration noise, scaling to the Box

  // Training workspaces (one gradient step allocates nothing while the batch size is
  // unchanged).
  Eigen::MatrixXf policy_noise_, next_noise_, next_actions_, actions_pi_, target_q_;
  Eigen::MatrixXf grad_actions_;
  // Per critic (they may run on different cores): d critic_loss / d Q_i, its loss, d actor_loss
  // / d Q_i and d actor_loss / d actions through critic i.
  std::vector<Eigen::MatrixXf> grad_q_, grad_min_q_, grad_critic_actions_;
  std::vector<double> critic_losses_;
  Eigen::RowVectorXf next_log_prob_, log_prob_, grad_log_prob_;
  // Acting workspaces.
  Eigen::MatrixXf scaled_actions_;
  Eigen::RowVectorXf acting_log_prob_;
};

}  // namespace rlrun
