#pragma once
// Deep Q-Network (Mnih et al. 2015, doi:10.1038/nature14236) with SB3 2.x semantics, defaults
// and key names (stable_baselines3/dqn/dqn.py, dqn/policies.py, common/off_policy_algorithm.py):
// an online Q-network and a target copy, epsilon-greedy exploration on a linear schedule,
// 1-step TD targets from the target network's max, Huber (smooth L1) loss, gradient-norm
// clipping, Adam with torch's defaults, and the target refreshed every
// target_update_interval env steps (counted per VecEnv step, divided by n_envs, as SB3).
// Collection, replay and the train_freq / gradient_steps cadence are OffPolicyAlgorithm's.
//
// One gradient step (train_on_batch, dqn.cpp) reads top to bottom like DQN.train's loop body.
// The Q-networks are SplitMlps and the optimizer a SplitAdam, so a training minibatch's parts
// run on the run's threads (AlgorithmSetup::pool, `--threads`), with the same bits on any number.
#include <cstdint>
#include <string>

#include "rlrun/algos/common/features_extractor_net.hpp"
#include "rlrun/algos/common/off_policy.hpp"
#include "rlrun/algos/dqn/exploration_schedule.hpp"
#include "rlrun/algos/dqn/q_network.hpp"
#include "rlrun/core/schedule.hpp"
#include "rlrun/nn/mlp.hpp"
#include "rlrun/nn/nature_cnn.hpp"
#include "rlrun/nn/split_adam.hpp"
#include "rlrun/nn/split_mlp.hpp"

namespace rlrun {

// SB3 DQN.__init__ defaults for the hyperparameters every off-policy algorithm shares.
inline OffPolicyConfig dqn_off_policy_defaults() {
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

class DQN : public OffPolicyAlgorithm {
 public:
  struct Config {
    Schedule learning_rate = Schedule::constant(1e-4);
    OffPolicyConfig off_policy = dqn_off_policy_defaults();
    int64_t target_update_interval = 10000;
    double exploration_fraction = 0.1;
    double exploration_initial_eps = 1.0;
    double exploration_final_eps = 0.05;
    double max_grad_norm = 10.0;
    QNetworkConfig policy;

    template <class V>
    void visit(V& v) {
      v("learning_rate", learning_rate, "Adam step size: a number or lin_<initial>",
        non_negative());
      off_policy.visit(v);  // buffer_size ... handle_timeout_termination, flattened as in SB3
      v("target_update_interval", target_update_interval,
        "env steps between target network updates", at_least(1));
      v("exploration_fraction", exploration_fraction,
        "fraction of training over which epsilon decays", in_range(0, 1).open_low());
      v("exploration_initial_eps", exploration_initial_eps,
        "initial epsilon (random action probability)", unit_interval());
      v("exploration_final_eps", exploration_final_eps, "final epsilon", unit_interval());
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

  // SB3 DQN.predict: greedy (deterministic) or epsilon-greedy with the current exploration
  // rate, one coin for the whole batch as SB3 draws it.
  void export_policy(PolicyGraph& graph, const std::string& obs, bool with_value) const override;
  void predict(const Eigen::Ref<const Eigen::MatrixXf>& obs, bool deterministic,
               Eigen::MatrixXf& actions) override;
  // Tensors `q_net.<i>.weight/bias`, `q_net_target.<i>.weight/bias` (SB3's policy state_dict
  // without its `q_net.` / `q_net_target.` module prefix) and the scalar `exploration_rate`
  // (SB3 saves it with the model; optional on load). A CnnPolicy's extractors under SB3's own
  // names: `q_net.features_extractor.cnn.0.weight`, ..., `q_net_target.features_extractor...`.
  void save(TensorMap& tensors) const override;
  void load(const TensorMap& tensors) override;

  // OffPolicyAlgorithm._sample_action: uniform actions before learning_starts, else predict()
  // with deterministic=False.
  void select_actions(const Eigen::MatrixXf& obs, bool warmup, Eigen::MatrixXf& env_actions,
                      Eigen::MatrixXf& buffer_actions) override;

  // One iteration of DQN.train's loop on `batch` with learning rate lr; returns the loss.
  // Public for tests and benchmarks: the (clipped) gradient stays in q_net().grads().
  double train_on_batch(const ReplayBatch& batch, float lr);
  // The TD targets of the last train_on_batch.
  const Eigen::RowVectorXf& td_targets() const { return targets_; }
  // The total gradient norm before clipping of the last train_on_batch.
  float last_grad_norm() const { return last_grad_norm_; }

  // Writable access (tests, tools) may change the weights: the acting copy is refreshed
  // before its next use.
  Mlp& q_net() {
    act_net_stale_ = true;
    return q_net_.net();
  }
  const Mlp& q_net() const { return q_net_.net(); }
  // The online network's NatureCNN (CnnPolicy; the first image key's for a
  // CombinedExtractor), or null.
  const NatureCnn* cnn() const { return extractor_.learned() ? &extractor_.cnn() : nullptr; }
  Mlp& q_net_target() { return q_net_target_.net(); }
  const Mlp& q_net_target() const { return q_net_target_.net(); }
  double exploration_rate() const { return exploration_rate_; }
  int64_t n_calls() const { return n_calls_; }

 private:
  // `gradient_steps` updates from the replay buffer (SB3 DQN.train), logging the mean loss.
  void train(int gradient_steps, Logger* logger) override;
  // SB3 DQN._on_step: the target update and the exploration schedule.
  void on_step(Logger* logger) override;
  void random_actions(Eigen::Index n, Eigen::MatrixXf& actions);

  Config config_;
  float action_start_ = 0.0f;  // Discrete(n, start): env action = start + Q-network index
  Rng action_rng_;
  // q_net's and q_net_target's features extractors (SB3's make_q_net builds one for each: a
  // NatureCNN for CnnPolicy) and the acting copy; the online one's networks have an Adam each
  // (SB3's one optimizer over q_net.parameters(), kept apart, the gradients clipped together).
  FeaturesExtractorNet extractor_, extractor_target_, act_extractor_;
  SplitMlp q_net_, q_net_target_;
  // A copy of q_net_ for acting (batch n_envs or the evaluator's), so that q_net_'s buffers
  // keep the training batch size and nothing reallocates; refreshed after each train().
  Mlp act_net_;
  bool act_net_stale_ = false;
  // SB3 2.x DQNPolicy: Adam over q_net's parameters only, torch defaults (eps 1e-8).
  SplitAdam optimizer_;
  std::vector<SplitAdam> extractor_optimizers_;  // an Adam per network of extractor_
  Eigen::MatrixXf grad_features_;                // dL/d(CNN features), features_dim x batch
  LinearDecay exploration_schedule_;
  double exploration_rate_ = 0.0;  // SB3 starts at 0 and sets it in the first _on_step
  int64_t n_calls_ = 0;

  // Training workspaces.
  Eigen::RowVectorXf targets_;  // 1 x batch
  Eigen::MatrixXf grad_q_;      // n_actions x batch
  float last_grad_norm_ = 0.0f;
  // Logger keys built once (a std::string per record would allocate every step).
  const std::string key_exploration_rate_ = "rollout/exploration_rate";
  const std::string key_learning_rate_ = "train/learning_rate";
  const std::string key_loss_ = "train/loss";
  const std::string key_n_updates_ = "train/n_updates";
};

}  // namespace rlrun
