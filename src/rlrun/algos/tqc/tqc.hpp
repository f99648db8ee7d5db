#pragma once
// Truncated Quantile Critics (Kuznetsov et al. 2020, "Controlling Overestimation Bias with
// Truncated Mixture of Continuous Distributional Quantile Critics", arXiv:2005.04269) with
// sb3-contrib 2.x semantics, defaults and key names (sb3_contrib/tqc/tqc.py, tqc/policies.py,
// common/utils.py quantile_huber_loss). It is SAC with distributional critics: SAC's actor,
// entropy coefficient, action selection and updates of the actor, the temperature and the
// targets (algos/common/entropy_regularized_actor_critic.hpp), and n_critics networks on
// concat(obs, action) that each output n_quantiles atoms of the return distribution. The
// target pools the target critics' atoms at (s', a'), drops the
// top_quantiles_to_drop_per_net * n_critics largest (the overestimation control), and backs up
// the rest with the entropy bonus; the critics follow it by the quantile Huber loss; the actor
// maximises the mean of all atoms minus alpha * log pi.
//
// One gradient step (train_on_batch, tqc.cpp) reads top to bottom like the paper's.
#include <string>
#include <vector>

#include "rlrun/algos/common/entropy_regularized_actor_critic.hpp"

namespace rlrun {

// sb3-contrib TQCPolicy / MlpPolicy keyword arguments (policy_kwargs in rl-zoo); the others
// are SAC's.
struct TqcPolicyConfig : EntropyRegularizedPolicyConfig {
  int n_quantiles = 25;  // atoms per critic network

  template <class V>
  void visit(V& v) {
    visit_fields(v, [this](V& w) {
      w("n_quantiles", n_quantiles, "atoms (quantiles) each critic network outputs",
        in_range(1, 10000));
      w("n_critics", n_critics, "quantile critic networks; the target pools their atoms",
        in_range(1, 100));
    });
  }
};

class TQC : public EntropyRegularizedActorCritic {
 public:
  // sb3-contrib TQC.__init__: SB3 SAC's arguments and defaults, and the truncation.
  struct Config : EntropyRegularizedConfig {
    int top_quantiles_to_drop_per_net = 2;
    TqcPolicyConfig policy;

    template <class V>
    void visit(V& v) {
      visit_fields(v, [this](V& w) {
        w("top_quantiles_to_drop_per_net", top_quantiles_to_drop_per_net,
          "largest target atoms dropped per critic network (overestimation control); below "
          "policy.n_quantiles",
          non_negative());
      });
      v("policy", policy,
        "networks: net_arch, activation_fn, n_quantiles, n_critics, gSDE options");
    }
  };

  static constexpr SpaceKind kActionSpaces[] = {SpaceKind::kBox};

  // Problems of `config` with these spaces (registry: checked before anything trains).
  static ConfigProblems check(const Config& config, const AlgorithmSetup& setup);

  // Throws std::invalid_argument for bad settings or spaces (bounded Box actions).
  TQC(const Config& config, const AlgorithmSetup& setup);

  // The deterministic action (SAC's policy). The value is TQC's estimate of Q(s, a) for that
  // action, the mean of every critic's atoms (what the actor maximises).
  void export_policy(PolicyGraph& graph, const std::string& obs, bool with_value) const override;

  // One gradient step of TQC.train.
  EntropyRegularizedStepStats train_on_batch(const ReplayBatch& batch, float lr,
                                             bool update_target) override;

  // n_critics * n_quantiles - top_quantiles_to_drop_per_net * n_critics.
  int n_target_quantiles() const;
  // From the last train_on_batch: the target atoms (n_target_quantiles x batch, ascending per
  // sample).
  const Eigen::MatrixXf& last_target_quantiles() const { return target_quantiles_; }

 private:
  int top_quantiles_to_drop_per_net_;
  Eigen::MatrixXf target_quantiles_, grad_quantiles_, pair_loss_, grad_critic_actions_;
  std::vector<const Eigen::MatrixXf*> next_quantiles_;
  std::vector<float> pooled_;
};

}  // namespace rlrun
