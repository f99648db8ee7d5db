#pragma once
// Truncated Quantile Critics (Kuznetsov et al. 2020, "Controlling Overestimation Bias with
// Truncated Mixture of Continuous Distributional Quantile Critics", arXiv:2005.04269) with
// sb3-contrib 2.x semantics, defaults and key names (sb3_contrib/tqc/tqc.py, tqc/policies.py,
// common/utils.py quantile_huber_loss). It is SAC with distributional critics: SAC's actor,
// entropy coefficient, action selection and off-policy loop (algos/common/), and n_critics
// networks on concat(obs, action) that each output n_quantiles atoms of the return
// distribution. The target pools the target critics' atoms at (s', a'), drops the
// top_quantiles_to_drop_per_net * n_critics largest (the overestimation control), and backs up
// the rest with the entropy bonus; the critics follow it by the quantile Huber loss; the actor
// maximises the mean of all atoms minus alpha * log pi.
//
// One gradient step (train_on_batch, tqc.cpp) reads top to bottom like TQC.train's loop body.
// The networks are SplitMlps: a training minibatch runs on both cores with RLRUN_THREADS=2,
// with the same bits as on one.
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

// sb3-contrib TQCPolicy / MlpPolicy keyword arguments (policy_kwargs in rl-zoo); the gSDE
// options are SAC's.
struct TqcPolicyConfig {
  NetArchPiQf net_arch = {{256, 256}, {256, 256}};  // actor (pi), each quantile critic (qf)
  Activation activation_fn = Activation::kReLU;     // nn.ReLU
  int n_quantiles = 25;                    // atoms per critic network
  int n_critics = 2;                       // quantile networks pooled in the target
  double log_std_init = -3.0;              // gSDE: initial log std
  bool full_std = true;                    // gSDE: a std per (latent feature, action)
  bool use_expln = false;                  // gSDE: expln instead of exp for the std
  double clip_mean = 2.0;                  // gSDE: Hardtanh bound on the mean (0 = none)

  template <class V>
  void visit(V& v) {
    v("net_arch", net_arch, kNetArchPiQfDoc, layer_width());
    v("activation_fn", activation_fn, kActivationFnDoc);
    v("n_quantiles", n_quantiles, "atoms (quantiles) each critic network outputs",
      in_range(1, 10000));
    v("n_critics", n_critics, "quantile critic networks; the target pools their atoms",
      in_range(1, 100));
    v("log_std_init", log_std_init, "gSDE (use_sde): initial log standard deviation",
      in_range(-20, 20));
    v("full_std", full_std,
      "gSDE (use_sde): log_std per latent feature and action (true) or per feature (false)");
    v("use_expln", use_expln, "gSDE (use_sde): expln instead of exp keeps the std positive");
    v("clip_mean", clip_mean, "gSDE (use_sde): clip the mean to [-clip_mean, clip_mean] (0: off)",
      in_range(0, 1e6));
  }
};

class TQC : public OffPolicyAlgorithm {
 public:
  struct Config {
    Schedule learning_rate = Schedule::constant(3e-4);
    OffPolicyConfig off_policy;  // sb3-contrib TQC defaults = SB3 SAC's
    std::string ent_coef = "auto";
    int target_update_interval = 1;
    std::string target_entropy = "auto";
    int top_quantiles_to_drop_per_net = 2;
    bool use_sde = false;
    int sde_sample_freq = -1;
    bool use_sde_at_warmup = false;
    TqcPolicyConfig policy;
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
      v("top_quantiles_to_drop_per_net", top_quantiles_to_drop_per_net,
        "largest target atoms dropped per critic network (overestimation control); below "
        "policy.n_quantiles",
        non_negative());
      v("use_sde", use_sde, "generalized State-Dependent Exploration (gSDE) instead of white noise");
      v("sde_sample_freq", sde_sample_freq,
        "gSDE: new noise matrix every N steps (-1: only at the start of each collection)");
      v("use_sde_at_warmup", use_sde_at_warmup,
        "gSDE: act with the policy's noise before learning_starts instead of uniform samples");
      v("policy", policy, "networks: net_arch, activation_fn, n_quantiles, n_critics, gSDE options");
    }
  };

  static constexpr SpaceKind kActionSpaces[] = {SpaceKind::kBox};

  // Problems of `config` with these spaces (registry: checked before anything trains).
  static ConfigProblems check(const Config& config, const AlgorithmSetup& setup);

  // Throws std::invalid_argument for bad settings or spaces (bounded Box actions).
  TQC(const Config& config, const AlgorithmSetup& setup);

  // tanh(mu) (deterministic) or a sample, rescaled to the Box bounds (SAC's policy).
  void export_policy(PolicyGraph& graph, const std::string& obs, bool with_value) const override;
  void predict(const Eigen::Ref<const Eigen::MatrixXf>& obs, bool deterministic,
               Eigen::MatrixXf& actions) override;
  // sb3-contrib TQCPolicy.state_dict(): actor.*, critic.qf<i>.*, critic_target.qf<i>.* (each
  // qf<i> ending in n_quantiles outputs), and log_ent_coef (learned) or ent_coef_tensor (fixed).
  void save(TensorMap& tensors) const override;
  void load(const TensorMap& tensors) override;

  // SB3 OffPolicyAlgorithm._sample_action, as SAC's.
  void select_actions(const Eigen::MatrixXf& obs, bool warmup, Eigen::MatrixXf& env_actions,
                      Eigen::MatrixXf& buffer_actions) override;

  // One gradient step of TQC.train on `batch` (actions in [-1, 1]) with learning rate lr;
  // update_target applies the Polyak update afterwards. Public for tests and benchmarks: the
  // gradients stay in the networks' grads() after the step.
  EntropyRegularizedStepStats train_on_batch(const ReplayBatch& batch, float lr, bool update_target);

  // n_critics * n_quantiles - top_quantiles_to_drop_per_net * n_critics.
  int n_target_quantiles() const;

  const Config& config() const { return config_; }
  const SacActor& actor() const { return actor_; }
  SacActor& actor() { return actor_; }
  const ContinuousCritic& critic() const { return critic_; }
  ContinuousCritic& critic() { return critic_; }
  const ContinuousCritic& critic_target() const { return critic_target_; }
  ContinuousCritic& critic_target() { return critic_target_; }
  const EntropyCoefficient& ent_coef() const { return ent_coef_; }
  // From the last train_on_batch: the target atoms (n_target_quantiles x batch, ascending per
  // sample) and the standard normal noise of the next actions and of the policy's actions.
  const Eigen::MatrixXf& last_target_quantiles() const { return target_quantiles_; }
  const Eigen::MatrixXf& last_next_noise() const { return next_noise_; }
  const Eigen::MatrixXf& last_policy_noise() const { return policy_noise_; }
  // gSDE: the acting actor's exploration matrices.
  const StateDependentNoise& acting_noise() { return acting_actor_.get().sde(); }

 private:
  void train(int gradient_steps, Logger* logger) override;
  void on_episode_end(int env) override { acting_.on_episode_end(env); }
  // gSDE: SB3 collect_rollouts' reset_noise points, as SAC's.
  void before_collect_step(int64_t collected_steps) override;
  // gSDE: train/std = actor.get_std().mean().
  void record_rollout_logs(Logger& logger) override;

  Config config_;
  int action_dim_ = 0;
  Rng train_rng_, predict_rng_;
  SacActor actor_;
  ContinuousCritic critic_, critic_target_;
  Adam actor_optimizer_;
  // One Adam over all critics' parameters in sb3-contrib; element-wise with one step count, so
  // one per critic is the same update.
  std::vector<Adam> critic_optimizers_;
  EntropyCoefficient ent_coef_;
  ActingCopy<SacActor> acting_actor_{actor_};
  BoxActionSelection acting_;

  // Training workspaces (one gradient step allocates nothing while the batch size is
  // unchanged).
  Eigen::MatrixXf policy_noise_, next_noise_, next_actions_, actions_pi_;
  Eigen::MatrixXf target_quantiles_, grad_quantiles_, pair_loss_, grad_critic_actions_,
      grad_actions_;
  std::vector<const Eigen::MatrixXf*> next_quantiles_;
  std::vector<float> pooled_;
  Eigen::RowVectorXf next_log_prob_, log_prob_, grad_log_prob_;
  // Acting workspaces.
  Eigen::MatrixXf scaled_actions_;
  Eigen::RowVectorXf acting_log_prob_;
};

}  // namespace rlrun
