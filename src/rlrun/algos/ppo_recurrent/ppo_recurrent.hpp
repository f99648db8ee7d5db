#pragma once
// RecurrentPPO: PPO with an LSTM policy, with sb3-contrib 2.4's semantics, defaults and key
// names (sb3_contrib/ppo_recurrent/ppo_recurrent.py, common/recurrent/). Where it differs from
// rlrun's PPO (algos/ppo/):
//   * the policy is RecurrentActorCriticPolicy (recurrent_policy.hpp): the rollouts carry each
//     env's LSTM states, zeroed where an episode starts, and keep every step's states;
//   * the update's minibatches are runs of the rollout, not shuffled samples: each epoch the
//     samples, flattened env by env, are rotated by a random offset and cut into consecutive
//     minibatches of batch_size; inside one, a sequence starts at the first sample, at every
//     episode start and at every change of env, and is replayed through the LSTMs from the
//     states stored at its first step (backpropagation through time over the sequence);
//   * defaults n_steps 128, batch_size 128, lstm_hidden_size 256; train/n_updates grows by
//     n_epochs per update, also when target_kl stops it early.
// The loss is PPO's (ppo_loss.hpp) over the minibatch's samples, as sb3-contrib's masked means
// are.
#include <optional>
#include <vector>

#include "rlrun/algos/common/on_policy.hpp"
#include "rlrun/algos/ppo/ppo_loss.hpp"
#include "rlrun/algos/ppo_recurrent/recurrent_policy.hpp"
#include "rlrun/core/schedule.hpp"
#include "rlrun/nn/adam.hpp"

namespace rlrun {

class RecurrentPPO : public OnPolicyAlgorithm {
 public:
  // sb3-contrib RecurrentPPO.__init__'s parameters and defaults.
  struct Config {
    Schedule learning_rate = Schedule::constant(3e-4);
    int n_steps = 128;
    int batch_size = 128;
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
    RecurrentPolicyConfig policy;

    template <class V>
    void visit(V& v) {
      v("learning_rate", learning_rate, "Adam step size: a number or lin_<initial>",
        non_negative());
      v("n_steps", n_steps, "steps per env per rollout (rollout size = n_steps * n_envs)",
        in_range(1, 1e8));
      v("batch_size", batch_size, "minibatch size (samples; split into sequences)",
        in_range(2, 1e8));
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
      v("policy", policy,
        "network: lstm_hidden_size, n_lstm_layers, shared_lstm, enable_critic_lstm, net_arch, "
        "activation_fn, ortho_init, log_std_init");
    }
  };

  // sb3-contrib's supported_action_spaces: every action space but Dict.
  static constexpr SpaceKind kActionSpaces[] = {SpaceKind::kBox, SpaceKind::kDiscrete,
                                                SpaceKind::kMultiDiscrete, SpaceKind::kMultiBinary};

  static ConfigProblems check(const Config& config, const AlgorithmSetup& setup);

  RecurrentPPO(const Config& config, const AlgorithmSetup& setup);

  // predict() without a state: every call from zero states, as sb3-contrib's predict(obs) with
  // state=None. recurrent_state_size()/predict_recurrent() carry the state (evaluation,
  // recording, Python's predict(state=..., episode_start=...)).
  void predict(const Eigen::Ref<const Eigen::MatrixXf>& obs, bool deterministic,
               Eigen::MatrixXf& actions) override;
  int recurrent_state_size() const override;
  int recurrent_layers() const override { return recurrent_.num_layers(); }
  void predict_recurrent(const Eigen::Ref<const Eigen::MatrixXf>& obs,
                         const Eigen::Ref<const Eigen::RowVectorXf>& episode_starts,
                         Eigen::MatrixXf& states, bool deterministic,
                         Eigen::MatrixXf& actions) override;
  void export_policy(PolicyGraph& graph, const std::string& obs, bool with_value) const override;
  void save(TensorMap& tensors) const override { recurrent_.save(tensors); }
  void load(const TensorMap& tensors) override { recurrent_.load(tensors); }

  const RecurrentActorCritic& recurrent_policy() const { return recurrent_; }

 private:
  RolloutPolicy& rollout_policy() override { return recurrent_; }
  // sb3-contrib RecurrentPPO.train: n_epochs over the rollout in minibatches of sequences.
  void train(double progress_remaining, Logger* logger) override;
  // Samples flat_[start, start + batch) as sequences (RecurrentRolloutBuffer._get_samples).
  void gather_sequences(int start, int batch);

  Config config_;
  RecurrentActorCritic recurrent_;
  Rng shuffle_rng_;
  Adam optimizer_;

  // flat_[i]: the rollout sample at sb3-contrib's flattened index i (env by env), rotated.
  std::vector<int> flat_;
  SequenceBatch sequences_;
  Lstm::State predict_state_;  // predict_recurrent's actor state (its caller keeps the real one)
  Eigen::MatrixXf mb_act_;
  Eigen::RowVectorXf mb_adv_, mb_ret_, mb_old_logp_, mb_old_val_;
  Eigen::RowVectorXf values_pred_, log_prob_, entropy_, grad_values_, grad_log_prob_, grad_entropy_;
};

}  // namespace rlrun
