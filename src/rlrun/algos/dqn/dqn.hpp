#pragma once
// Deep Q-Network (Mnih et al. 2015, doi:10.1038/nature14236) with SB3 2.x semantics, defaults
// and key names (stable_baselines3/dqn/dqn.py, dqn/policies.py, common/off_policy_algorithm.py):
// an online Q-network and a target copy, epsilon-greedy exploration on a linear schedule,
// 1-step TD targets from the target network's max, Huber (smooth L1) loss, gradient-norm
// clipping, Adam with torch's defaults, and the target refreshed every
// target_update_interval env steps (counted per VecEnv step, divided by n_envs, as SB3).
// Collection, replay and the train_freq / gradient_steps cadence are OffPolicyAlgorithm's; the
// networks, acting, the target update and the model's tensors are QLearningAlgorithm's (shared
// with QR-DQN). One gradient step (train_on_batch, dqn.cpp) reads top to bottom like DQN.train's
// loop body.
#include <cstdint>
#include <string>

#include "rlrun/algos/common/off_policy.hpp"
#include "rlrun/algos/common/q_learning_algorithm.hpp"
#include "rlrun/core/schedule.hpp"

namespace rlrun {

class DQN : public QLearningAlgorithm {
 public:
  // SB3 DQN.__init__'s hyperparameters: QLearningConfig's (learning_rate, buffer_size ...
  // exploration_final_eps, with DQN's defaults), then these.
  struct Config : QLearningConfig {
    double max_grad_norm = 10.0;
    QNetworkConfig policy;

    template <class V>
    void visit(V& v) {
      QLearningConfig::visit(v);
      v("max_grad_norm", max_grad_norm, "global gradient-norm clipping", positive());
      v("policy", policy, "Q-network: net_arch, activation_fn");
    }
  };

  // SB3 DQN: supported_action_spaces=(spaces.Discrete,).
  static constexpr SpaceKind kActionSpaces[] = {SpaceKind::kDiscrete};

  // Problems of `config` with these spaces (registry: checked before anything trains).
  static ConfigProblems check(const Config& config, const AlgorithmSetup& setup);

  // Throws std::invalid_argument for a non-Box observation space, a non-Discrete action space
  // or an out-of-range hyperparameter.
  DQN(const Config& config, const AlgorithmSetup& setup);

  // One iteration of DQN.train's loop on `batch` with learning rate lr; returns the loss.
  double train_on_batch(const ReplayBatch& batch, float lr) override;
  // The TD targets of the last train_on_batch.
  const Eigen::RowVectorXf& td_targets() const { return targets_; }

 private:
  // DQN's network outputs are the Q-values.
  const Eigen::MatrixXf& q_values(const Eigen::MatrixXf& outputs) override { return outputs; }
  std::string export_q_values(PolicyGraph&, const std::string& outputs) const override {
    return outputs;
  }

  Config config_;
  // Training workspaces.
  Eigen::RowVectorXf targets_;  // 1 x batch
  Eigen::MatrixXf grad_q_;      // n_actions x batch
};

}  // namespace rlrun
