#pragma once
// Soft Actor-Critic (Haarnoja et al. 2018, arXiv:1801.01290 and arXiv:1812.05905) with SB3 2.x
// semantics, defaults and key names (stable_baselines3/sac/sac.py, sac/policies.py,
// common/off_policy_algorithm.py; CleanRL's sac_continuous_action.py is the same update in
// one file): n_critics (2) Q-networks with clipped double-Q soft Bellman targets, around the
// maximum-entropy actor-critic SAC shares with TQC (algos/common/
// entropy_regularized_actor_critic.hpp: the tanh-squashed Gaussian actor, the entropy
// coefficient, acting in a Box, the actor and temperature steps, the target update).
//
// One gradient step (train_on_batch, sac.cpp) reads top to bottom like the paper's.
#include <string>
#include <vector>

#include "rlrun/algos/common/entropy_regularized_actor_critic.hpp"

namespace rlrun {

// SB3 SACPolicy / MlpPolicy keyword arguments (policy_kwargs in rl-zoo).
struct SacPolicyConfig : EntropyRegularizedPolicyConfig {
  template <class V>
  void visit(V& v) {
    visit_fields(v, [this](V& w) {
      w("n_critics", n_critics, "number of Q-networks; targets use their minimum",
        in_range(1, 100));
    });
  }
};

class SAC : public EntropyRegularizedActorCritic {
 public:
  // SB3 SAC.__init__ (its defaults are EntropyRegularizedConfig's).
  struct Config : EntropyRegularizedConfig {
    SacPolicyConfig policy;

    template <class V>
    void visit(V& v) {
      visit_fields(v, [](V&) {});
      v("policy", policy, "networks: net_arch, activation_fn, n_critics, gSDE options");
    }
  };

  static constexpr SpaceKind kActionSpaces[] = {SpaceKind::kBox};

  // Problems of `config` with these spaces (registry: checked before anything trains).
  static ConfigProblems check(const Config& config, const AlgorithmSetup& setup);

  // Throws std::invalid_argument for bad settings or spaces (bounded Box actions).
  SAC(const Config& config, const AlgorithmSetup& setup);

  // The deterministic action; the value is the first critic's Q(s, a) of that action.
  void export_policy(PolicyGraph& graph, const std::string& obs, bool with_value) const override;

  // One gradient step of SAC.train.
  EntropyRegularizedStepStats train_on_batch(const ReplayBatch& batch, float lr,
                                             bool update_target) override;

  // From the last train_on_batch: the soft Bellman target y (1 x batch).
  const Eigen::MatrixXf& last_critic_target() const { return target_q_; }

 private:
  Eigen::MatrixXf target_q_;
  // Per critic (they may run on different cores): d critic_loss / d Q_i, its loss, d actor_loss
  // / d Q_i and d actor_loss / d actions through critic i.
  std::vector<Eigen::MatrixXf> grad_q_, grad_min_q_, grad_critic_actions_;
  std::vector<double> critic_losses_;
};

}  // namespace rlrun
