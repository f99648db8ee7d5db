#pragma once
// What DQN and QR-DQN share (SB3 dqn/dqn.py, sb3-contrib qrdqn/qrdqn.py: the two classes are the
// same outside train() and the network's output): an online network over the features of the
// observation and a target copy, epsilon-greedy acting on a linear schedule, the target refreshed
// every target_update_interval env steps (per VecEnv step, divided by n_envs), Adam over the
// online network (its CNN included), optional gradient-norm clipping, and the model's tensors
// under SB3's names. Each algorithm keeps its whole update (train_on_batch) in its own file.
//
// The networks are SplitMlps and the optimizer a SplitAdam, so a training minibatch's parts run
// on the run's threads (AlgorithmSetup::pool, `--threads`), with the same bits on any number.
#include <Eigen/Core>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "rlrun/algos/common/exploration_schedule.hpp"
#include "rlrun/algos/common/features_extractor_net.hpp"
#include "rlrun/algos/common/off_policy.hpp"
#include "rlrun/algos/common/q_network.hpp"
#include "rlrun/core/schedule.hpp"
#include "rlrun/nn/adam.hpp"
#include "rlrun/nn/mlp.hpp"
#include "rlrun/nn/nature_cnn.hpp"
#include "rlrun/nn/split_adam.hpp"
#include "rlrun/nn/split_mlp.hpp"

namespace rlrun {

// SB3 DQN.__init__ defaults for the hyperparameters every off-policy algorithm shares (QR-DQN's
// are the same).
inline OffPolicyConfig q_learning_off_policy_defaults() {
  OffPolicyConfig c;
  c.buffer_size = 1000000;
  c.learning_starts = 100;
  c.batch_size = 32;
  c.tau = 1.0;
  c.gamma = 0.99;
  c.train_freq = TrainFreq{4, false};
  c.gradient_steps = 1;
  return c;
}

// The hyperparameters DQN's and QR-DQN's Configs share, with DQN's defaults (QR-DQN's Config
// sets its own), visited in SB3's order.
struct QLearningConfig {
  Schedule learning_rate = Schedule::constant(1e-4);
  OffPolicyConfig off_policy = q_learning_off_policy_defaults();
  int64_t target_update_interval = 10000;
  double exploration_fraction = 0.1;
  double exploration_initial_eps = 1.0;
  double exploration_final_eps = 0.05;

  template <class V>
  void visit(V& v) {
    v("learning_rate", learning_rate, "Adam step size: a number or lin_<initial>", non_negative());
    off_policy.visit(v);  // buffer_size ... handle_timeout_termination, flattened as in SB3
    v("target_update_interval", target_update_interval, "env steps between target network updates",
      at_least(1));
    v("exploration_fraction", exploration_fraction,
      "fraction of training over which epsilon decays", in_range(0, 1).open_low());
    v("exploration_initial_eps", exploration_initial_eps,
      "initial epsilon (random action probability)", unit_interval());
    v("exploration_final_eps", exploration_final_eps, "final epsilon", unit_interval());
  }
};

// What the shared part takes from DQN's or QR-DQN's Config.
struct QLearningSettings {
  Schedule learning_rate;
  int64_t target_update_interval = 10000;
  LinearDecay exploration;
  QNetworkConfig policy;
  // Outputs of the network per action: 1 for DQN's Q-values, n_quantiles for QR-DQN.
  int outputs_per_action = 1;
  AdamConfig adam;
  // The online network's state_dict name (SB3 "q_net", sb3-contrib "quantile_net"); the target's
  // is it + "_target".
  std::string network_name;
};

// The settings of `config` with the algorithm's network and optimizer.
QLearningSettings q_learning_settings(const QLearningConfig& config, const QNetworkConfig& policy,
                                      int outputs_per_action, const AdamConfig& adam,
                                      std::string network_name);

// The Q-network family's checks: the extractor of each network, the memory of the online and
// target networks (n_actions * outputs_per_action outputs) and the replay buffer's.
void check_q_learning(ConfigProblems& out, const OffPolicyConfig& off_policy,
                      const QNetworkConfig& policy, int outputs_per_action,
                      const AlgorithmSetup& setup);

// What the family adds to its config's field checks, before any network is built: Discrete
// actions (SB3 supported_action_spaces) and a target network that moves (tau > 0). Throws
// std::invalid_argument naming `algo`.
void require_q_learning_setup(const std::string& algo, const OffPolicyConfig& off_policy,
                              const AlgorithmSetup& setup);

class QLearningAlgorithm : public OffPolicyAlgorithm {
 public:
  // predict(deterministic): the greedy action, start + argmax Q; the value is every Q-value.
  void export_policy(PolicyGraph& graph, const std::string& obs, bool with_value) const final;
  // SB3 DQN.predict: greedy (deterministic) or epsilon-greedy with the current exploration
  // rate, one coin for the whole batch as SB3 draws it.
  void predict(const Eigen::Ref<const Eigen::MatrixXf>& obs, bool deterministic,
               Eigen::MatrixXf& actions) final;
  // Tensors `<name>.<i>.weight/bias`, `<name>_target.<i>.weight/bias` (SB3's policy state_dict
  // without its module prefix), a CnnPolicy's extractors under `<name>.features_extractor.cnn.*`
  // and `<name>_target.features_extractor...`, and the scalar `exploration_rate` (SB3 saves it
  // with the model; optional on load).
  void save(TensorMap& tensors) const final;
  void load(const TensorMap& tensors) final;
  // OffPolicyAlgorithm._sample_action: uniform actions before learning_starts, else predict()
  // with deterministic=False. The buffer stores the network's index (= the env action when the
  // Discrete space starts at 0, as SB3 assumes).
  void select_actions(const Eigen::MatrixXf& obs, bool warmup, Eigen::MatrixXf& env_actions,
                      Eigen::MatrixXf& buffer_actions) final;

  // One gradient step on `batch` with learning rate lr; returns the loss. Public for tests and
  // benchmarks: the (clipped) gradient stays in q_net().grads().
  virtual double train_on_batch(const ReplayBatch& batch, float lr) = 0;
  // The total gradient norm before clipping of the last train_on_batch (0 without clipping).
  float last_grad_norm() const { return last_grad_norm_; }

  // The online network (DQN's q_net, QR-DQN's quantile_net). Writable access (tests, tools)
  // may change the weights: the acting copy is refreshed before its next use.
  Mlp& q_net() {
    act_net_stale_ = true;
    return q_net_.net();
  }
  const Mlp& q_net() const { return q_net_.net(); }
  Mlp& q_net_target() { return q_net_target_.net(); }
  const Mlp& q_net_target() const { return q_net_target_.net(); }
  // The online network's NatureCNN (CnnPolicy; the first image key's for a CombinedExtractor),
  // or null.
  const NatureCnn* cnn() const { return extractor_.learned() ? &extractor_.cnn() : nullptr; }
  double exploration_rate() const { return exploration_rate_; }
  int64_t n_calls() const { return n_calls_; }

 protected:
  // `off_policy` and `settings` as the algorithm's constructor validated them.
  QLearningAlgorithm(std::string id, const OffPolicyConfig& off_policy, const AlgorithmSetup& setup,
                     QLearningSettings settings, const ReplayStream& replay);

  // Q(s, a) of every action from a network's outputs, n_actions x batch (DQN: the outputs
  // themselves; QR-DQN: the mean of each action's quantiles). Valid until the next call.
  virtual const Eigen::MatrixXf& q_values(const Eigen::MatrixXf& outputs) = 0;
  // The same as graph nodes, from the node of the network's outputs.
  virtual std::string export_q_values(PolicyGraph& graph, const std::string& outputs) const = 0;

  // The target network's outputs on the batch's next observations (torch.no_grad()).
  const Eigen::MatrixXf& target_outputs(const ReplayBatch& b);
  // The online network's outputs on the batch's observations, kept for backward_and_step.
  const Eigen::MatrixXf& online_outputs(const ReplayBatch& b);
  // optimizer.zero_grad(); loss.backward() from dL/d(outputs) — through the features into the
  // CNN, if any; clip_grad_norm_ over all of the online network's parameters when
  // max_grad_norm is set; optimizer.step().
  void backward_and_step(const Eigen::MatrixXf& grad_outputs, float lr,
                         std::optional<double> max_grad_norm);
  // The Discrete action of a replay-buffer row, checked: buffers come from checkpoints too.
  Eigen::Index buffer_action(const ReplayBatch& b, Eigen::Index j) const;
  int n_actions() const { return n_actions_; }
  int outputs_per_action() const { return settings_.outputs_per_action; }

 private:
  // `gradient_steps` updates from the replay buffer (SB3 DQN.train), logging the mean loss.
  void train(int gradient_steps, Logger* logger) final;
  // SB3 DQN._on_step: the target update and the exploration schedule.
  void on_step(Logger* logger) final;
  void random_actions(Eigen::Index n, Eigen::MatrixXf& actions);

  QLearningSettings settings_;
  double tau_ = 1.0;  // OffPolicyConfig::tau of the target update
  int n_actions_ = 0;
  float action_start_ = 0.0f;  // Discrete(n, start): env action = start + network index
  Rng action_rng_;
  // The online and target networks' features extractors (SB3's make_q_net builds one for each: a
  // NatureCNN for CnnPolicy) and the acting copy; the online one's networks have an Adam each
  // (SB3's one optimizer over the online network's parameters, kept apart, clipped together).
  FeaturesExtractorNet extractor_, extractor_target_, act_extractor_;
  SplitMlp q_net_, q_net_target_;
  // A copy of q_net_ for acting (batch n_envs or the evaluator's), so that q_net_'s buffers
  // keep the training batch size and nothing reallocates; refreshed after each train().
  Mlp act_net_;
  bool act_net_stale_ = false;
  SplitAdam optimizer_;
  std::vector<SplitAdam> extractor_optimizers_;  // an Adam per network of extractor_
  Eigen::MatrixXf grad_features_;                // dL/d(CNN features), features_dim x batch
  double exploration_rate_ = 0.0;  // SB3 starts at 0 and sets it in the first _on_step
  int64_t n_calls_ = 0;
  float last_grad_norm_ = 0.0f;
  // Logger keys built once (a std::string per record would allocate every step).
  const std::string key_exploration_rate_ = "rollout/exploration_rate";
  const std::string key_learning_rate_ = "train/learning_rate";
  const std::string key_loss_ = "train/loss";
  const std::string key_n_updates_ = "train/n_updates";
};

}  // namespace rlrun
