#pragma once
// Proximal Policy Optimization (Schulman et al. 2017, arXiv:1707.06347) with SB3's semantics,
// defaults and key names (stable_baselines3/ppo/ppo.py, common/on_policy_algorithm.py):
// rollouts of n_steps per env with timeout bootstrapping, GAE, n_epochs of shuffled
// minibatches, clipped surrogate, optional clipped value loss, advantage normalisation,
// global gradient-norm clipping, Adam (eps 1e-5 as SB3's ActorCriticPolicy sets it).
#include <optional>
#include <string>

#include "rlrun/algos/common/actor_critic_policy.hpp"
#include "rlrun/algos/common/config_checks.hpp"
#include "rlrun/algos/common/on_policy.hpp"
#include "rlrun/algos/ppo/ppo_loss.hpp"
#include "rlrun/core/schedule.hpp"
#include "rlrun/nn/adam.hpp"

namespace rlrun {

class PPO : public OnPolicyAlgorithm {
 public:
  struct Config {
    Schedule learning_rate = Schedule::constant(3e-4);
    int n_steps = 2048;
    int batch_size = 64;
    int n_epochs = 10;
    double gamma = 0.99;
    double gae_lambda = 0.95;
    Schedule clip_range = Schedule::constant(0.2);
    std::optional<Schedule> clip_range_vf;
    bool normalize_advantage = true;
    double ent_coef = 0.0;
    double vf_coef = 0.5;
    double max_grad_norm = 0.5;
    bool use_sde = false;
    int sde_sample_freq = -1;
    std::optional<double> target_kl;
    ActorCriticPolicyConfig policy;

    template <class V>
    void visit(V& v) {
      v("learning_rate", learning_rate, "Adam step size: a number or lin_<initial>",
        non_negative());
      v("n_steps", n_steps, "steps per env per rollout (rollout size = n_steps * n_envs)",
        in_range(1, 1e8));
      // SB3 ppo.py: "batch_size > 1 ... required for advantage normalization".
      v("batch_size", batch_size, "minibatch size", in_range(2, 1e8));
      v("n_epochs", n_epochs, "passes over each rollout", in_range(1, 1e6));
      v("gamma", gamma, "discount factor", unit_interval());
      v("gae_lambda", gae_lambda, "GAE bias/variance trade-off", unit_interval());
      v("clip_range", clip_range, "surrogate clipping: a number or lin_<initial>", positive());
      v("clip_range_vf", clip_range_vf, "value clipping around old values (null = off)",
        positive());
      v("normalize_advantage", normalize_advantage, "normalise advantages per minibatch");
      v("ent_coef", ent_coef, "entropy bonus coefficient", non_negative());
      v("vf_coef", vf_coef, "value loss coefficient", non_negative());
      v("max_grad_norm", max_grad_norm, "global gradient-norm clipping", positive());
      v("use_sde", use_sde, "generalized State-Dependent Exploration (gSDE) for Box actions");
      v("sde_sample_freq", sde_sample_freq,
        "gSDE: new noise matrix every N steps (-1: only at the start of each rollout)");
      v("target_kl", target_kl,
        "stop an update's epochs when approx KL > 1.5 * target_kl (null = off)", positive());
      v("policy", policy, "network: net_arch, activation_fn, ortho_init, log_std_init");
    }
  };

  // SB3's support table (docs/guide/algos.rst): every action space but Dict.
  static constexpr SpaceKind kActionSpaces[] = {SpaceKind::kBox, SpaceKind::kDiscrete,
                                                SpaceKind::kMultiDiscrete, SpaceKind::kMultiBinary};

  // Problems of `config` with these spaces (registry: checked before anything trains).
  static ConfigProblems check(const Config& config, const AlgorithmSetup& setup);

  PPO(const Config& config, const AlgorithmSetup& setup);

 protected:
  // MaskablePPO (algos/ppo_mask/) is this update with the rollout's action masks.
  struct Masking {
    bool maskable = false;     // MaskableActorCriticPolicy, rollouts read and keep masks
    bool use_masking = false;  // the loss's log-probs and entropy use the stored masks
  };
  PPO(std::string id, const Config& config, const AlgorithmSetup& setup, Masking masking);

 private:
  // SB3 PPO.train: n_epochs over the rollout in shuffled minibatches of the clipped surrogate,
  // the (optionally clipped) value loss and the entropy bonus (sb3-contrib MaskablePPO.train:
  // the same with the rollout's masks).
  void train(double progress_remaining, Logger* logger) override;
  // The minibatch of rollout columns indices_[start, start + batch) into the mb_ workspaces
  // (SB3 RolloutBuffer.get; masks too when they are used, MaskableRolloutBuffer.get).
  void gather_minibatch(int start, int batch);

  Config config_;
  Masking masking_;
  Rng shuffle_rng_;
  Adam optimizer_;

  // Minibatch workspaces, allocated once in the constructor.
  std::vector<int> indices_;
  Eigen::MatrixXf mb_obs_, mb_act_, mb_masks_;
  Eigen::RowVectorXf mb_adv_, mb_ret_, mb_old_logp_, mb_old_val_;
  Eigen::RowVectorXf values_pred_, log_prob_, entropy_, grad_values_, grad_log_prob_, grad_entropy_;
};

}  // namespace rlrun
