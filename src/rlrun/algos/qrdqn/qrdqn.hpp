#pragma once
// Quantile Regression DQN (Dabney et al. 2017, "Distributional Reinforcement Learning with
// Quantile Regression", arXiv:1710.10044) with sb3-contrib 2.4's semantics, defaults and key
// names (sb3_contrib/qrdqn/qrdqn.py, qrdqn/policies.py): the network outputs n_quantiles
// quantiles of the return per action (torch's view(-1, n_quantiles, n_actions): output row
// k * n_actions + a), Q(s, a) is their mean, the target takes the target network's quantiles at
// its greedy action, and the loss is the quantile Huber loss summed over the current quantiles
// and averaged over the batch and the target quantiles. Adam with eps = 0.01 / batch_size (the
// paper's, as sb3-contrib sets it), no gradient clipping unless max_grad_norm is set.
//
// Acting, the target update, epsilon-greedy exploration and the model's tensors are DQN's
// (QLearningAlgorithm); the whole update is train_on_batch (qrdqn.cpp), top to bottom like
// QRDQN.train's loop body.
#include <Eigen/Core>
#include <cstdint>
#include <optional>
#include <string>

#include "rlrun/algos/common/off_policy.hpp"
#include "rlrun/algos/common/q_learning_algorithm.hpp"
#include "rlrun/core/schedule.hpp"

namespace rlrun {

// sb3-contrib QRDQNPolicy's kwargs: QNetwork's (net_arch [64, 64], nn.ReLU, the features
// extractor) and n_quantiles.
struct QuantileNetworkConfig : QNetworkConfig {
  int n_quantiles = 200;

  template <class V>
  void visit(V& v) {
    QNetworkConfig::visit(v);
    v("n_quantiles", n_quantiles, "quantiles of the return per action", in_range(1, 10000));
  }
};

class QRDQN : public QLearningAlgorithm {
 public:
  // sb3-contrib QRDQN.__init__'s hyperparameters: DQN's (QLearningConfig) with QR-DQN's
  // defaults, then these.
  struct Config : QLearningConfig {
    std::optional<double> max_grad_norm;  // None: no clipping (sb3-contrib's default)
    QuantileNetworkConfig policy;

    Config() {
      learning_rate = Schedule::constant(5e-5);
      exploration_fraction = 0.005;
      exploration_final_eps = 0.01;
    }

    template <class V>
    void visit(V& v) {
      QLearningConfig::visit(v);
      v("max_grad_norm", max_grad_norm, "global gradient-norm clipping (unset: none)", positive());
      v("policy", policy, "quantile network: net_arch, activation_fn, n_quantiles");
    }
  };

  // sb3-contrib QRDQN: supported_action_spaces=(spaces.Discrete,).
  static constexpr SpaceKind kActionSpaces[] = {SpaceKind::kDiscrete};

  // Problems of `config` with these spaces (registry: checked before anything trains).
  static ConfigProblems check(const Config& config, const AlgorithmSetup& setup);

  // Throws std::invalid_argument for a non-Discrete action space or an out-of-range
  // hyperparameter.
  QRDQN(const Config& config, const AlgorithmSetup& setup);

  // One iteration of QRDQN.train's loop on `batch` with learning rate lr; returns the loss.
  double train_on_batch(const ReplayBatch& batch, float lr) override;
  // The target quantiles of the last train_on_batch, n_quantiles x batch.
  const Eigen::MatrixXf& target_quantiles() const { return target_quantiles_; }
  int n_quantiles() const { return outputs_per_action(); }

 private:
  // Q(s, a) = the mean of a's quantiles (QuantileNetwork._predict: self(obs).mean(dim=1)).
  const Eigen::MatrixXf& q_values(const Eigen::MatrixXf& outputs) override;
  std::string export_q_values(PolicyGraph& graph, const std::string& outputs) const override;

  Config config_;
  // Training and acting workspaces.
  Eigen::MatrixXf q_mean_;              // n_actions x batch
  Eigen::MatrixXf target_quantiles_;    // n_quantiles x batch
  Eigen::MatrixXf current_quantiles_;   // n_quantiles x batch, at the taken actions
  Eigen::MatrixXf grad_current_, rho_;  // the loss's workspaces (quantile_huber_loss)
  Eigen::MatrixXf grad_outputs_;        // (n_quantiles * n_actions) x batch
};

}  // namespace rlrun
