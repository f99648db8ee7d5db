#pragma once
// Advantage Actor-Critic (Mnih et al. 2016, synchronous variant) with SB3's semantics and
// defaults (stable_baselines3/a2c/a2c.py): n_steps 5 rollouts, one gradient step on the whole
// rollout, loss = -mean(A log pi) + vf_coef mse(R, V) - ent_coef mean(H), RMSprop
// (alpha 0.99, eps 1e-5) by default, advantages not normalised, GAE lambda 1 (plain n-step
// returns).
#include <optional>

#include "rlrun/algos/common/actor_critic_policy.hpp"
#include "rlrun/algos/common/config_checks.hpp"
#include "rlrun/algos/common/on_policy.hpp"
#include "rlrun/core/schedule.hpp"
#include "rlrun/nn/adam.hpp"
#include "rlrun/nn/rmsprop.hpp"

namespace rlrun {

class A2C : public OnPolicyAlgorithm {
 public:
  struct Config {
    Schedule learning_rate = Schedule::constant(7e-4);
    int n_steps = 5;
    double gamma = 0.99;
    double gae_lambda = 1.0;
    double ent_coef = 0.0;
    double vf_coef = 0.5;
    double max_grad_norm = 0.5;
    double rms_prop_eps = 1e-5;
    bool use_sde = false;
    int sde_sample_freq = -1;
    bool use_rms_prop = true;
    bool normalize_advantage = false;
    ActorCriticPolicyConfig policy;

    template <class V>
    void visit(V& v) {
      v("learning_rate", learning_rate, "optimizer step size: a number or lin_<initial>",
        non_negative());
      v("n_steps", n_steps, "steps per env per update (rollout size = n_steps * n_envs)",
        in_range(1, 1e8));
      v("gamma", gamma, "discount factor", unit_interval());
      v("gae_lambda", gae_lambda, "GAE lambda (1 = n-step returns)", unit_interval());
      v("ent_coef", ent_coef, "entropy bonus coefficient", non_negative());
      v("vf_coef", vf_coef, "value loss coefficient", non_negative());
      v("max_grad_norm", max_grad_norm, "global gradient-norm clipping", positive());
      v("rms_prop_eps", rms_prop_eps, "RMSprop epsilon", positive());
      v("use_rms_prop", use_rms_prop, "RMSprop (true, SB3 default) or Adam");
      v("use_sde", use_sde, "generalized State-Dependent Exploration (gSDE) for Box actions");
      v("sde_sample_freq", sde_sample_freq,
        "gSDE: new noise matrix every N steps (-1: only at the start of each rollout)");
      v("normalize_advantage", normalize_advantage, "normalise advantages over the rollout");
      v("policy", policy, "network: net_arch, activation_fn, ortho_init, log_std_init");
    }
  };
  // SB3's support table (docs/guide/algos.rst): every action space but Dict.
  static constexpr SpaceKind kActionSpaces[] = {SpaceKind::kBox, SpaceKind::kDiscrete,
                                                SpaceKind::kMultiDiscrete, SpaceKind::kMultiBinary};

  // Problems of `config` with these spaces (registry: checked before anything trains).
  static ConfigProblems check(const Config& config, const AlgorithmSetup& setup);

  A2C(const Config& config, const AlgorithmSetup& setup);

 private:
  // SB3 A2C.train: one gradient step on the whole rollout.
  void train(double progress_remaining, Logger* logger) override;

  Config config_;
  std::optional<RmsProp> rmsprop_;
  std::optional<Adam> adam_;

  Eigen::MatrixXf obs_;  // the rollout's observations as floats (uint8 images are bytes there)
  Eigen::RowVectorXf advantages_, returns_, values_, log_prob_, entropy_, grad_values_,
      grad_log_prob_, grad_entropy_;
};

}  // namespace rlrun
