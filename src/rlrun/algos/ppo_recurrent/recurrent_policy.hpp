#pragma once
// sb3-contrib 2.4's RecurrentActorCriticPolicy (sb3_contrib/common/recurrent/policies.py,
// MlpLstmPolicy / CnnLstmPolicy / MultiInputLstmPolicy): the features extractor, then an LSTM
// for the actor (`lstm_actor`) and, for the critic, one of
//   * its own LSTM (`lstm_critic`, enable_critic_lstm true, the default),
//   * the actor's LSTM, whose output the critic reads detached (shared_lstm true: the value
//     loss does not train the LSTM),
//   * a Linear from the features to lstm_hidden_size (`critic`, both false; no activation),
// then SB3's towers and heads (mlp_extractor, action_net, value_net, log_std) on those outputs.
// The towers and heads are an ActorCriticPolicy built on a Box of lstm_hidden_size floats (the
// algorithm owns it); this class puts the recurrent layers in front of it and keeps the envs'
// recurrent states for the rollouts (the RolloutPolicy of on_policy.hpp): before each step the
// state of every env whose observation starts an episode is zeroed (_process_sequence).
// Initialisation as sb3-contrib's: orthogonal with SB3's gains for the extractor, towers and
// heads (ortho_init), torch's defaults for the LSTMs and the critic's Linear.
#include <Eigen/Core>
#include <vector>

#include "rlrun/algos/common/actor_critic_policy.hpp"
#include "rlrun/algos/common/rollout_policy.hpp"
#include "rlrun/nn/lstm.hpp"

namespace rlrun {

// sb3-contrib's policy_kwargs: SB3's ActorCriticPolicy ones and the LSTM's.
struct RecurrentPolicyConfig : ActorCriticPolicyConfig {
  int lstm_hidden_size = 256;
  int n_lstm_layers = 1;
  bool shared_lstm = false;
  bool enable_critic_lstm = true;

  template <class V>
  void visit(V& v) {
    ActorCriticPolicyConfig::visit(v);
    v("lstm_hidden_size", lstm_hidden_size, "hidden units of each LSTM layer", in_range(1, 65536));
    v("n_lstm_layers", n_lstm_layers, "stacked LSTM layers", in_range(1, 64));
    v("shared_lstm", shared_lstm,
      "the critic reads the actor's LSTM (detached: only the actor's loss trains it)");
    v("enable_critic_lstm", enable_critic_lstm,
      "the critic has its own LSTM (false with shared_lstm false: a Linear layer instead)");
  }
};

// What is wrong with the LSTM settings (sb3-contrib's assertions), or nothing.
ConfigProblems check_recurrent_policy(const RecurrentPolicyConfig& config);

// The recurrent state of n sequences: the actor's LSTM and the critic's (the actor's again
// with shared_lstm; unused with a Linear critic, which keeps the actor's, as sb3-contrib does).
struct RnnStates {
  Lstm::State pi, vf;
};

// A minibatch of sequences for the update (RecurrentPPO::train): observations time-major and
// padded (obs_dim x max_length * n_seq, column t * n_seq + s), the episode-start flags of the
// same columns, each sequence's initial states, and for each sample of the minibatch (in its
// order) its column.
struct SequenceBatch {
  Eigen::MatrixXf obs;
  Eigen::RowVectorXf episode_starts;
  Eigen::Index n_seq = 0;
  RnnStates initial;
  std::vector<Eigen::Index> sample_columns;
};

class RecurrentActorCritic final : public RolloutPolicy {
 public:
  // `heads` is the algorithm's ActorCriticPolicy on Box(lstm_hidden_size); rollouts run
  // `n_envs` envs for `n_steps` steps and keep each step's states for the update.
  RecurrentActorCritic(const Space& observation_space, const RecurrentPolicyConfig& config,
                       ActorCriticPolicy& heads, Rng& init_rng, int n_envs, int n_steps);

  int hidden_size() const { return lstm_actor_.hidden_size(); }
  int num_layers() const { return lstm_actor_.num_layers(); }
  RnnStates zero_states(Eigen::Index n) const;

  // RolloutPolicy: the rollout's steps with the envs' states (kept per step, before the step's
  // reset, as sb3-contrib's buffer stores _last_lstm_states).
  bool use_sde() const override { return heads_.use_sde(); }
  void reset_noise(Rng& rng, int n_envs) override { heads_.reset_noise(rng, n_envs); }
  void act(int step, const Eigen::MatrixXf& obs, const Eigen::RowVectorXf& episode_starts, Rng& rng,
           Eigen::MatrixXf& actions, Eigen::RowVectorXf& values, Eigen::RowVectorXf& log_probs,
           const Eigen::MatrixXf* masks) override;
  float terminal_value(const Eigen::MatrixXf& final_obs, int env) override;
  void last_values(const Eigen::MatrixXf& obs, const Eigen::RowVectorXf& episode_starts,
                   Eigen::RowVectorXf& values) override;

  // The states kept at rollout sample k = step * n_envs + env (before that step's reset), and
  // the envs' current states.
  void stored_states(Eigen::Index k, RnnStates& out, Eigen::Index column) const;
  const RnnStates& current_states() const { return states_; }

  // predict() with memory (sb3-contrib's predict(state, episode_start)): the actor's LSTM
  // state in and out.
  void predict(const Eigen::Ref<const Eigen::MatrixXf>& obs,
               const Eigen::Ref<const Eigen::RowVectorXf>& episode_starts, Lstm::State& actor_state,
               Rng& rng, bool deterministic, Eigen::MatrixXf& actions);

  // Deploying (nn/policy_graph.hpp): one step of the deterministic policy from `obs` and the
  // graph's state input (the actor LSTM's h and c of every layer, predict()'s state), the
  // heads' export on its output, and the next state as the state output. With `with_value`
  // the critic's V(s) too: from the actor's latent (shared_lstm), the Linear critic, or the
  // critic's own LSTM, whose state then follows the actor's in the graph's state.
  void export_to(PolicyGraph& graph, const std::string& obs, const Space& action_space,
                 bool with_value) const;

  // The update's forward pass (evaluate_actions on a SequenceBatch): values, log-probs and
  // entropies of the minibatch's samples, in its order; backward() takes their loss gradients.
  void evaluate_actions(const SequenceBatch& batch,
                        const Eigen::Ref<const Eigen::MatrixXf>& actions,
                        Eigen::RowVectorXf& values, Eigen::RowVectorXf& log_prob,
                        Eigen::RowVectorXf& entropy);
  void backward(const Eigen::Ref<const Eigen::RowVectorXf>& grad_values,
                const Eigen::Ref<const Eigen::RowVectorXf>& grad_log_prob,
                const Eigen::Ref<const Eigen::RowVectorXf>& grad_entropy);

  // Every parameter: the heads' blocks, then the extractor's, the LSTMs' and the critic's.
  std::vector<ParamBlock> param_blocks();
  void zero_grad();

  // sb3-contrib's state_dict names: features_extractor.*, lstm_actor.*, lstm_critic.* or
  // critic.*, and the heads' (mlp_extractor.*, action_net.*, value_net.*, log_std).
  void save(TensorMap& tensors) const;
  void load(const TensorMap& tensors);

  // Resume: the envs' current states (their shape is the configuration's).
  void write_state(StateWriter out) const;
  void read_state(const StateReader& in);

 private:
  enum class Critic { kLstm, kSharedLstm, kLinear };
  // The features of the encoded observations (the extractor keeps what its backward needs).
  Eigen::Ref<const Eigen::MatrixXf> features(const Eigen::Ref<const Eigen::MatrixXf>& obs);
  // Both latents of `features` (columns time-major for `n` sequences) from `states`, which
  // receive the final states.
  void latents(const Eigen::Ref<const Eigen::MatrixXf>& features,
               const Eigen::Ref<const Eigen::RowVectorXf>& starts, Eigen::Index n,
               RnnStates& states);
  // The critic's latent alone (predict_values).
  void value_latent(const Eigen::Ref<const Eigen::MatrixXf>& features,
                    const Eigen::Ref<const Eigen::RowVectorXf>& starts, Eigen::Index n,
                    Lstm::State& vf_state);

  ActorCriticPolicy& heads_;
  ObservationEncoder encoder_;
  FeaturesExtractorNet extractor_;
  Lstm lstm_actor_, lstm_critic_;
  Mlp critic_linear_;  // Linear(features_dim, lstm_hidden_size) (Critic::kLinear)
  Critic critic_ = Critic::kLstm;

  RnnStates states_;  // the envs' current states
  // Per rollout sample k: the actor's and critic's h and c, (layers * H) x (n_steps * n_envs).
  Eigen::MatrixXf stored_pi_h_, stored_pi_c_, stored_vf_h_, stored_vf_c_;
  int n_envs_ = 1;

  // Workspaces.
  Eigen::MatrixXf latent_pi_, latent_vf_, mb_latent_pi_, mb_latent_vf_;
  Eigen::MatrixXf grad_pi_, grad_vf_, grad_pi_pad_, grad_vf_pad_, grad_features_, grad_more_;
  std::vector<Eigen::Index> columns_;  // the last evaluate_actions' sample columns
  Eigen::RowVectorXf no_starts_, scratch_values_, scratch_log_probs_;
};

}  // namespace rlrun
