#pragma once
// MaskablePPO: PPO with invalid-action masking (Huang and Ontañón 2020, arXiv:2006.14171) with
// sb3-contrib 2.4's semantics, defaults and key names (sb3_contrib/ppo_mask/ppo_mask.py,
// common/maskable/). It is rlrun's PPO (algos/ppo/, whose update takes the masks) where
// sb3-contrib's differs:
//   * the policy is MaskableActorCriticPolicy (algos/common/actor_critic_policy.hpp with
//     `maskable`): illegal actions' logits are -1e8 before the softmax, the entropy sums over
//     the legal ones, MultiBinary is one two-way categorical per entry (2n logits);
//   * rollouts read every step's masks from the envs (env/action_mask.hpp) and the buffer
//     keeps them (MaskableRolloutBuffer); the loss's log-probs and entropy use them;
//   * Discrete, MultiDiscrete and MultiBinary actions only; no gSDE (use_sde is fixed False);
//   * train/n_updates grows by n_epochs per update even when target_kl stops it early, and
//     there is no train/std.
// predict_masked() acts with masks (rlrun eval / record and Python's predict(action_masks=)
// pass the env's); predict() without masks uses the unmasked distribution, as sb3-contrib's
// predict(action_masks=None).
#include <optional>

#include "rlrun/algos/ppo/ppo.hpp"
#include "rlrun/core/schedule.hpp"

namespace rlrun {

class MaskablePPO : public PPO {
 public:
  // sb3-contrib MaskablePPO.__init__'s parameters and defaults (PPO's, without gSDE).
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
    std::optional<double> target_kl;
    bool use_masking = true;
    ActorCriticPolicyConfig policy;

    template <class V>
    void visit(V& v) {
      v("learning_rate", learning_rate, "Adam step size: a number or lin_<initial>",
        non_negative());
      v("n_steps", n_steps, "steps per env per rollout (rollout size = n_steps * n_envs)",
        in_range(1, 1e8));
      v("batch_size", batch_size, "minibatch size", in_range(2, 1e8));
      v("n_epochs", n_epochs, "passes over each rollout", in_range(1, 1e6));
      v("gamma", gamma, "discount factor", unit_interval());
      v("gae_lambda", gae_lambda, "GAE bias/variance trade-off", unit_interval());
      v("clip_range", clip_range, "surrogate clipping: a number or lin_<initial>", positive());
      v("clip_range_vf", clip_range_vf, "value clipping around old values (null = off)",
        positive());
      v("normalize_advantage", normalize_advantage, "normalise advantages per minibatch");
      v("ent_coef", ent_coef, "entropy bonus coefficient (entropy of the masked distribution)",
        non_negative());
      v("vf_coef", vf_coef, "value loss coefficient", non_negative());
      v("max_grad_norm", max_grad_norm, "global gradient-norm clipping", positive());
      v("target_kl", target_kl,
        "stop an update's epochs when approx KL > 1.5 * target_kl (null = off)", positive());
      // sb3-contrib's learn(use_masking=...) and evaluate_policy(use_masking=...).
      v("use_masking", use_masking,
        "read the env's action masks in rollouts and evaluation (false: act unmasked, as "
        "sb3-contrib's learn(use_masking=False))");
      v("policy", policy, "network: net_arch, activation_fn, ortho_init");
    }
  };

  // sb3-contrib's supported_action_spaces: Discrete, MultiDiscrete, MultiBinary.
  static constexpr SpaceKind kActionSpaces[] = {SpaceKind::kDiscrete, SpaceKind::kMultiDiscrete,
                                                SpaceKind::kMultiBinary};

  static ConfigProblems check(const Config& config, const AlgorithmSetup& setup);

  MaskablePPO(const Config& config, const AlgorithmSetup& setup);

 private:
  // PPO's settings with gSDE off (sb3-contrib's MaskablePPO has none).
  static PPO::Config ppo_config(const Config& config);
};

}  // namespace rlrun
