#include "rlrun/algos/ppo_recurrent/recurrent_policy.hpp"

#include <cmath>
#include <stdexcept>

#include "rlrun/core/state_dict.hpp"
#include "rlrun/nn/policy_graph.hpp"

namespace rlrun {

ConfigProblems check_recurrent_policy(const RecurrentPolicyConfig& config) {
  ConfigProblems out;
  // sb3-contrib RecurrentActorCriticPolicy.__init__'s assertions.
  if (config.shared_lstm && config.enable_critic_lstm)
    out.push_back({"policy.shared_lstm",
                   "shared_lstm and enable_critic_lstm are both true: choose between a shared "
                   "LSTM, a separate one or none for the critic (set enable_critic_lstm: false)"});
  if (config.features_extractor_class != FeaturesExtractor::kFlatten &&
      !config.share_features_extractor)
    out.push_back({"policy.share_features_extractor",
                   "RecurrentPPO reads one features extractor for actor and critic in rlrun "
                   "(share_features_extractor: true)"});
  return out;
}

RecurrentActorCritic::RecurrentActorCritic(const Space& observation_space,
                                           const RecurrentPolicyConfig& config,
                                           ActorCriticPolicy& heads, Rng& init_rng, int n_envs,
                                           int n_steps)
    : heads_(heads),
      encoder_(observation_space,
               encoder_normalizes_images(config.features_extractor_class, config.normalize_images)),
      n_envs_(n_envs) {
  extractor_ =
      FeaturesExtractorNet(config.extractor(), observation_space, encoder_.features_dim(), nullptr);
  const int features = extractor_.out_dim(), H = config.lstm_hidden_size;
  critic_ = config.enable_critic_lstm ? Critic::kLstm
            : config.shared_lstm      ? Critic::kSharedLstm
                                      : Critic::kLinear;
  // Made (and drawn) in sb3-contrib's order: the extractor with the towers (SB3's _build),
  // then lstm_actor, then the critic's Linear or LSTM.
  if (config.ortho_init)
    extractor_.init_orthogonal(init_rng, std::sqrt(2.0f));
  else
    extractor_.init_torch_default(init_rng);
  lstm_actor_ = Lstm(features, H, config.n_lstm_layers);
  lstm_actor_.init_torch_default(init_rng);
  if (critic_ == Critic::kLinear) {
    critic_linear_ = Mlp(features, {}, H, Activation::kTanh);  // one Linear: no activation
    critic_linear_.init_torch_default(init_rng);
  } else if (critic_ == Critic::kLstm) {
    lstm_critic_ = Lstm(features, H, config.n_lstm_layers);
    lstm_critic_.init_torch_default(init_rng);
  }
  states_ = zero_states(n_envs);
  const Eigen::Index rows = Eigen::Index{config.n_lstm_layers} * H;
  const Eigen::Index samples = Eigen::Index{n_steps} * n_envs;
  for (Eigen::MatrixXf* m : {&stored_pi_h_, &stored_pi_c_, &stored_vf_h_, &stored_vf_c_})
    m->setZero(rows, samples);
}

RnnStates RecurrentActorCritic::zero_states(Eigen::Index n) const {
  return {lstm_actor_.zero_state(n), lstm_actor_.zero_state(n)};
}

Eigen::Ref<const Eigen::MatrixXf> RecurrentActorCritic::features(
    const Eigen::Ref<const Eigen::MatrixXf>& obs) {
  return extractor_.forward(encoder_(obs));
}

void RecurrentActorCritic::latents(const Eigen::Ref<const Eigen::MatrixXf>& features,
                                   const Eigen::Ref<const Eigen::RowVectorXf>& starts,
                                   Eigen::Index n, RnnStates& states) {
  latent_pi_ = lstm_actor_.forward(features, starts, n, states.pi);
  switch (critic_) {
    case Critic::kLstm: latent_vf_ = lstm_critic_.forward(features, starts, n, states.vf); break;
    case Critic::kSharedLstm:
      // sb3-contrib: latent_vf = latent_pi.detach(), the critic's states the actor's.
      latent_vf_ = latent_pi_;
      states.vf = states.pi;
      break;
    case Critic::kLinear:
      latent_vf_ = critic_linear_.forward(features);
      states.vf = states.pi;
      break;
  }
}

void RecurrentActorCritic::value_latent(const Eigen::Ref<const Eigen::MatrixXf>& features,
                                        const Eigen::Ref<const Eigen::RowVectorXf>& starts,
                                        Eigen::Index n, Lstm::State& vf_state) {
  // sb3-contrib predict_values: the critic's LSTM, the actor's with shared_lstm (from the
  // states it is given), or the Linear.
  switch (critic_) {
    case Critic::kLstm: latent_vf_ = lstm_critic_.forward(features, starts, n, vf_state); break;
    case Critic::kSharedLstm:
      latent_vf_ = lstm_actor_.forward(features, starts, n, vf_state);
      break;
    case Critic::kLinear: latent_vf_ = critic_linear_.forward(features); break;
  }
}

void RecurrentActorCritic::act(int step, const Eigen::MatrixXf& obs,
                               const Eigen::RowVectorXf& episode_starts, Rng& rng,
                               Eigen::MatrixXf& actions, Eigen::RowVectorXf& values,
                               Eigen::RowVectorXf& log_probs, const Eigen::MatrixXf* masks) {
  // rollout_buffer.add(..., lstm_states=self._last_lstm_states): the states before this step.
  const Eigen::Index first = Eigen::Index{step} * n_envs_;
  stored_pi_h_.middleCols(first, n_envs_) = states_.pi.h;
  stored_pi_c_.middleCols(first, n_envs_) = states_.pi.c;
  stored_vf_h_.middleCols(first, n_envs_) = states_.vf.h;
  stored_vf_c_.middleCols(first, n_envs_) = states_.vf.c;
  latents(features(obs), episode_starts, obs.cols(), states_);
  heads_.act_on_latents(latent_pi_, latent_vf_, rng, false, actions, values, log_probs, masks);
}

float RecurrentActorCritic::terminal_value(const Eigen::MatrixXf& final_obs, int env) {
  // sb3-contrib collect_rollouts: the critic's new state of that env, no episode start.
  Lstm::State vf{states_.vf.h.col(env), states_.vf.c.col(env)};
  no_starts_.setZero(1);
  value_latent(features(final_obs), no_starts_, 1, vf);
  heads_.predict_values(latent_vf_, scratch_values_);
  return scratch_values_(0);
}

void RecurrentActorCritic::last_values(const Eigen::MatrixXf& obs,
                                       const Eigen::RowVectorXf& episode_starts,
                                       Eigen::RowVectorXf& values) {
  Lstm::State vf = states_.vf;  // predict_values does not move the rollout's states on
  value_latent(features(obs), episode_starts, obs.cols(), vf);
  heads_.predict_values(latent_vf_, values);
}

void RecurrentActorCritic::stored_states(Eigen::Index k, RnnStates& out,
                                         Eigen::Index column) const {
  out.pi.h.col(column) = stored_pi_h_.col(k);
  out.pi.c.col(column) = stored_pi_c_.col(k);
  out.vf.h.col(column) = stored_vf_h_.col(k);
  out.vf.c.col(column) = stored_vf_c_.col(k);
}

void RecurrentActorCritic::predict(const Eigen::Ref<const Eigen::MatrixXf>& obs,
                                   const Eigen::Ref<const Eigen::RowVectorXf>& episode_starts,
                                   Lstm::State& actor_state, Rng& rng, bool deterministic,
                                   Eigen::MatrixXf& actions) {
  // sb3-contrib predict -> get_distribution: the actor's LSTM only (predict's state is the
  // actor's (h, c)). The heads' value output is not used.
  latent_pi_ = lstm_actor_.forward(features(obs), episode_starts, obs.cols(), actor_state);
  heads_.act_on_latents(latent_pi_, latent_pi_, rng, deterministic, actions, scratch_values_,
                        scratch_log_probs_);
}

void RecurrentActorCritic::export_to(PolicyGraph& graph, const std::string& obs,
                                     const Space& action_space, bool with_value) const {
  const std::string features = extractor_.export_to(graph, encoder_.export_to(graph, obs));
  const int actor_state = lstm_actor_.state_size();
  const bool critic_state = with_value && critic_ == Critic::kLstm;
  const std::string state =
      graph.add_state_input(actor_state + (critic_state ? lstm_critic_.state_size() : 0));
  const PolicyGraph::LstmStep actor =
      graph.lstm(features, lstm_actor_, graph.slice(state, 0, actor_state));
  heads_.export_to(graph, actor.output, action_space, /*with_value=*/false);
  if (!with_value) {
    graph.set_state_output(actor.next_state);
    return;
  }
  switch (critic_) {
    case Critic::kLstm: {
      const PolicyGraph::LstmStep critic = graph.lstm(
          features, lstm_critic_, graph.slice(state, actor_state, lstm_critic_.state_size()));
      graph.set_value(heads_.export_value(graph, critic.output));
      graph.set_state_output(graph.concat({actor.next_state, critic.next_state}));
      return;
    }
    case Critic::kSharedLstm: graph.set_value(heads_.export_value(graph, actor.output)); break;
    case Critic::kLinear:
      graph.set_value(heads_.export_value(graph, graph.mlp(features, critic_linear_)));
      break;
  }
  graph.set_state_output(actor.next_state);
}

void RecurrentActorCritic::evaluate_actions(const SequenceBatch& batch,
                                            const Eigen::Ref<const Eigen::MatrixXf>& actions,
                                            Eigen::RowVectorXf& values,
                                            Eigen::RowVectorXf& log_prob,
                                            Eigen::RowVectorXf& entropy) {
  RnnStates states = batch.initial;
  latents(features(batch.obs), batch.episode_starts, batch.n_seq, states);
  // The padded columns only carry the sequences along: the loss reads the samples' columns
  // (sb3-contrib's mask).
  columns_ = batch.sample_columns;
  const Eigen::Index n = static_cast<Eigen::Index>(columns_.size());
  mb_latent_pi_.resize(latent_pi_.rows(), n);
  mb_latent_vf_.resize(latent_vf_.rows(), n);
  for (Eigen::Index j = 0; j < n; ++j) {
    mb_latent_pi_.col(j) = latent_pi_.col(columns_[j]);
    mb_latent_vf_.col(j) = latent_vf_.col(columns_[j]);
  }
  heads_.evaluate_latents(mb_latent_pi_, mb_latent_vf_, actions, values, log_prob, entropy);
}

void RecurrentActorCritic::backward(const Eigen::Ref<const Eigen::RowVectorXf>& grad_values,
                                    const Eigen::Ref<const Eigen::RowVectorXf>& grad_log_prob,
                                    const Eigen::Ref<const Eigen::RowVectorXf>& grad_entropy) {
  heads_.backward_latents(grad_values, grad_log_prob, grad_entropy, &grad_pi_, &grad_vf_);
  const Eigen::Index padded = latent_pi_.cols();
  grad_pi_pad_.setZero(grad_pi_.rows(), padded);
  grad_vf_pad_.setZero(grad_vf_.rows(), padded);
  for (size_t j = 0; j < columns_.size(); ++j) {
    grad_pi_pad_.col(columns_[j]) = grad_pi_.col(static_cast<Eigen::Index>(j));
    grad_vf_pad_.col(columns_[j]) = grad_vf_.col(static_cast<Eigen::Index>(j));
  }
  const bool learned = extractor_.learned();
  lstm_actor_.backward(grad_pi_pad_, learned ? &grad_features_ : nullptr);
  // A shared LSTM's critic latent is detached: its gradient stops here.
  if (critic_ == Critic::kLstm)
    lstm_critic_.backward(grad_vf_pad_, learned ? &grad_more_ : nullptr);
  if (critic_ == Critic::kLinear)
    critic_linear_.backward(grad_vf_pad_, learned ? &grad_more_ : nullptr);
  if (!learned) return;
  if (critic_ != Critic::kSharedLstm) grad_features_ += grad_more_;
  extractor_.backward(grad_features_);
}

std::vector<ParamBlock> RecurrentActorCritic::param_blocks() {
  std::vector<ParamBlock> blocks = heads_.param_blocks();
  for (const ParamBlock& b : extractor_.blocks()) blocks.push_back(b);
  blocks.push_back(lstm_actor_.block());
  if (critic_ == Critic::kLstm) blocks.push_back(lstm_critic_.block());
  if (critic_ == Critic::kLinear) blocks.push_back(critic_linear_.block());
  return blocks;
}

void RecurrentActorCritic::zero_grad() {
  heads_.zero_grad();
  extractor_.zero_grad();
  lstm_actor_.zero_grad();
  lstm_critic_.zero_grad();
  critic_linear_.zero_grad();
}

void RecurrentActorCritic::save(TensorMap& tensors) const {
  heads_.save(tensors);
  extractor_.save("features_extractor", tensors);
  lstm_actor_.save("lstm_actor", tensors);
  if (critic_ == Critic::kLstm) lstm_critic_.save("lstm_critic", tensors);
  if (critic_ == Critic::kLinear) save_mlp(critic_linear_, "critic", "critic", tensors);
}

void RecurrentActorCritic::load(const TensorMap& tensors) {
  heads_.load(tensors);
  extractor_.load("features_extractor", tensors);
  lstm_actor_.load("lstm_actor", tensors);
  if (critic_ == Critic::kLstm) lstm_critic_.load("lstm_critic", tensors);
  if (critic_ == Critic::kLinear) load_mlp(critic_linear_, "critic", "critic", tensors);
}

void RecurrentActorCritic::write_state(StateWriter out) const {
  put_matrix(out, "pi_h", states_.pi.h);
  put_matrix(out, "pi_c", states_.pi.c);
  put_matrix(out, "vf_h", states_.vf.h);
  put_matrix(out, "vf_c", states_.vf.c);
}

void RecurrentActorCritic::read_state(const StateReader& in) {
  get_matrix(in, "pi_h", states_.pi.h);
  get_matrix(in, "pi_c", states_.pi.c);
  get_matrix(in, "vf_h", states_.vf.h);
  get_matrix(in, "vf_c", states_.vf.c);
}

}  // namespace rlrun
