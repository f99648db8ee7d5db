#pragma once
// Trust Region Policy Optimization (Schulman et al. 2015, arXiv:1502.05477) with sb3-contrib
// 2.4's semantics, defaults and key names (sb3_contrib/trpo/trpo.py): SB3's on-policy rollouts
// and GAE (algos/common/on_policy.hpp) and ActorCriticPolicy, then per rollout
//   1. the surrogate objective's gradient g on the whole rollout (every sub_sampling_factor-th
//      sample of a shuffled copy), advantages normalised;
//   2. the step direction s ~ F^-1 g by conjugate gradient (cg_max_steps, damping cg_damping),
//      F the Fisher information: the Hessian of the mean KL(new || old)
//      (ActorCriticPolicy::fisher_vector_product);
//   3. the largest step sqrt(2 target_kl / s.F s) s, shrunk by line_search_shrinking_factor
//      until the objective improves and the KL stays under target_kl (line_search_max_iter
//      tries; none: the actor keeps its parameters);
//   4. n_critic_updates epochs of the value MSE in minibatches of batch_size, Adam (eps 1e-5,
//      SB3's ActorCriticPolicy optimizer) on the critic only: the actor's gradients are dropped
//      ("otherwise it defeats the purposes of the KL constraint").
// No entropy bonus, no value coefficient, no gradient clipping. Policies with a learned features
// extractor (CnnPolicy) are not built for TRPO yet: the Fisher product runs through the MLP.
#include "rlrun/algos/common/actor_critic_policy.hpp"
#include "rlrun/algos/common/config_checks.hpp"
#include "rlrun/algos/common/on_policy.hpp"
#include "rlrun/core/schedule.hpp"
#include "rlrun/nn/adam.hpp"

namespace rlrun {

class TRPO : public OnPolicyAlgorithm {
 public:
  // sb3-contrib TRPO.__init__'s parameters and defaults.
  struct Config {
    Schedule learning_rate = Schedule::constant(1e-3);
    int n_steps = 2048;
    int batch_size = 128;
    double gamma = 0.99;
    int cg_max_steps = 15;
    double cg_damping = 0.1;
    double line_search_shrinking_factor = 0.8;
    int line_search_max_iter = 10;
    int n_critic_updates = 10;
    double gae_lambda = 0.95;
    bool use_sde = false;
    int sde_sample_freq = -1;
    bool normalize_advantage = true;
    double target_kl = 0.01;
    int sub_sampling_factor = 1;
    ActorCriticPolicyConfig policy;

    template <class V>
    void visit(V& v) {
      v("learning_rate", learning_rate,
        "Adam step size of the value function: a number or lin_<initial>", non_negative());
      v("n_steps", n_steps, "steps per env per rollout (rollout size = n_steps * n_envs)",
        in_range(1, 1e8));
      v("batch_size", batch_size, "minibatch size of the value function's updates",
        in_range(1, 1e8));
      v("gamma", gamma, "discount factor", unit_interval());
      v("cg_max_steps", cg_max_steps, "conjugate gradient iterations for the step direction",
        in_range(0, 1e4));
      v("cg_damping", cg_damping, "damping added to the Fisher-vector products", non_negative());
      v("line_search_shrinking_factor", line_search_shrinking_factor,
        "step-size factor per backtracking try", in_range(1e-6, 1));
      v("line_search_max_iter", line_search_max_iter, "backtracking tries", in_range(1, 1e4));
      v("n_critic_updates", n_critic_updates, "value-function epochs per rollout",
        in_range(0, 1e6));
      v("gae_lambda", gae_lambda, "GAE bias/variance trade-off", unit_interval());
      v("use_sde", use_sde, "generalized State-Dependent Exploration (gSDE) for Box actions");
      v("sde_sample_freq", sde_sample_freq,
        "gSDE: new noise matrix every N steps (-1: only at the start of each rollout)");
      v("normalize_advantage", normalize_advantage, "normalise advantages over the rollout");
      v("target_kl", target_kl, "KL divergence bound of one policy update", positive());
      v("sub_sampling_factor", sub_sampling_factor,
        "policy step on every n-th sample of the rollout (Schulman's thesis pp. 40-42)",
        in_range(1, 1e6));
      v("policy", policy, "network: net_arch, activation_fn, ortho_init, log_std_init");
    }
  };

  // sb3-contrib's supported_action_spaces: every action space but Dict.
  static constexpr SpaceKind kActionSpaces[] = {SpaceKind::kBox, SpaceKind::kDiscrete,
                                                SpaceKind::kMultiDiscrete, SpaceKind::kMultiBinary};

  static ConfigProblems check(const Config& config, const AlgorithmSetup& setup);

  TRPO(const Config& config, const AlgorithmSetup& setup);

 private:
  // sb3-contrib TRPO.train: one natural-gradient step of the actor with a line search, then
  // the critic's epochs.
  void train(double progress_remaining, Logger* logger) override;
  // Steps 1-3 on the policy batch (batch_obs_, ...): the surrogate's gradient, the conjugate
  // gradient direction and the line search. Records policy_objective, kl_divergence_loss and
  // is_line_search_success.
  void update_actor(double& objective, double& kl, bool& success);
  // Step 4: returns the mean value loss over every minibatch.
  double update_critic(float lr);
  // A fresh permutation of the rollout (SB3 RolloutBuffer.get's np.random.permutation).
  void shuffle();
  // (1/n) sum advantages * exp(log_prob - old_log_prob) for the batch, log_prob_ current.
  double surrogate() const;

  Config config_;
  Rng rng_;  // permutations and conjugate gradient's start
  Adam critic_optimizer_;
  std::vector<int> indices_;
  Eigen::MatrixXf batch_obs_, batch_act_, mb_obs_;
  Eigen::RowVectorXf batch_adv_, batch_old_logp_, mb_ret_;
  Eigen::RowVectorXf values_, log_prob_, entropy_, grad_values_, grad_log_prob_, grad_entropy_;
};

}  // namespace rlrun
