#include "rlrun/algos/ppo_recurrent/ppo_recurrent.hpp"

#include <algorithm>
#include <numeric>
#include <utility>

#include "rlrun/algos/common/rng_streams.hpp"
#include "rlrun/core/config_validation.hpp"
#include "rlrun/nn/clip_grad.hpp"
#include "rlrun/nn/policy_graph.hpp"

namespace rlrun {

namespace {
// The towers' and heads' configuration: on the LSTM's outputs, so no extractor of their own.
ActorCriticPolicyConfig heads_config(const RecurrentPolicyConfig& policy) {
  ActorCriticPolicyConfig heads = policy;
  heads.features_extractor_class = FeaturesExtractor::kFlatten;
  return heads;
}

Space lstm_output_space(const RecurrentPPO::Config& config) {
  return Space::box(-1.0f, 1.0f, {config.policy.lstm_hidden_size});
}
}  // namespace

ConfigProblems RecurrentPPO::check(const Config& config, const AlgorithmSetup& setup) {
  const int64_t rollout = static_cast<int64_t>(config.n_steps) * setup.n_envs;
  ConfigProblems out = check_actor_critic(config.policy, rollout,
                                          std::min<int64_t>(config.batch_size, rollout), setup);
  for (ConfigProblem& p : check_recurrent_policy(config.policy)) out.push_back(std::move(p));
  if (config.normalize_advantage && rollout < 2)
    out.push_back({"n_steps", "n_steps * n_envs must be > 1 to normalise advantages"});
  check_use_sde(out, config.use_sde, setup);
  return out;
}

RecurrentPPO::RecurrentPPO(const Config& config, const AlgorithmSetup& setup)
    : OnPolicyAlgorithm("RecurrentPPO", setup,
                        lstm_output_space(valid_config(config, "RecurrentPPO")),
                        heads_config(config.policy),
                        {config.n_steps, config.gamma, config.gae_lambda, config.use_sde,
                         config.sde_sample_freq}),
      config_(config),
      recurrent_([&]() -> RecurrentActorCritic {
        Rng init_rng(setup.seed ^ kRecurrentInitStream);
        return RecurrentActorCritic(setup.observation_space, config.policy, policy_, init_rng,
                                    setup.n_envs, config.n_steps);
      }()),
      shuffle_rng_(setup.seed ^ kSampleStream) {
  AdamConfig adam;
  adam.eps = 1e-5;  // SB3's ActorCriticPolicy optimizer_kwargs
  optimizer_ = Adam(recurrent_.param_blocks(), adam);
  checkpoint("optimizer", optimizer_);
  checkpoint("shuffle_rng", shuffle_rng_);
  checkpoint("lstm_states", recurrent_);
  flat_.resize(static_cast<size_t>(config_.n_steps) * setup.n_envs);
}

void RecurrentPPO::train(double progress_remaining, Logger* logger) {
  const float lr = static_cast<float>(config_.learning_rate(progress_remaining));
  const float clip_range = static_cast<float>(config_.clip_range(progress_remaining));
  std::optional<float> clip_range_vf;
  if (config_.clip_range_vf)
    clip_range_vf = static_cast<float>((*config_.clip_range_vf)(progress_remaining));
  const int size = static_cast<int>(flat_.size());
  const int n_steps = config_.n_steps, n_envs = setup_.n_envs;

  PpoTrainStatistics statistics;
  bool continue_training = true;
  std::vector<ParamBlock> blocks = recurrent_.param_blocks();
  for (int epoch = 0; epoch < config_.n_epochs && continue_training; ++epoch) {
    statistics.start_epoch();
    // RecurrentRolloutBuffer.get: the samples env by env (swap_and_flatten), the order kept but
    // rotated by a random split index ("trick to shuffle a bit").
    const int split = static_cast<int>(shuffle_rng_.below(static_cast<uint64_t>(size)));
    for (int i = 0; i < size; ++i) {
      const int f = (split + i) % size;  // flattened index: env f / n_steps, step f % n_steps
      flat_[static_cast<size_t>(i)] = (f % n_steps) * n_envs + f / n_steps;
    }
    for (int start = 0; start < size; start += config_.batch_size) {
      gather_sequences(start, std::min(config_.batch_size, size - start));
      recurrent_.evaluate_actions(sequences_, mb_act_, values_pred_, log_prob_, entropy_);
      if (config_.normalize_advantage) normalize_advantages(mb_adv_);
      const PpoLossTerms t = ppo_loss(
          {values_pred_, log_prob_, entropy_, mb_old_logp_, mb_old_val_, mb_adv_, mb_ret_},
          clip_range, clip_range_vf, static_cast<float>(config_.ent_coef),
          static_cast<float>(config_.vf_coef), grad_values_, grad_log_prob_, grad_entropy_);
      statistics.add(t);
      if (config_.target_kl && t.approx_kl > 1.5 * *config_.target_kl) {
        continue_training = false;
        break;
      }
      recurrent_.zero_grad();
      recurrent_.backward(grad_values_, grad_log_prob_, grad_entropy_);
      clip_grad_norm(blocks, static_cast<float>(config_.max_grad_norm));
      optimizer_.step(lr);
    }
  }
  // ppo_recurrent.py: `self._n_updates += self.n_epochs` after the loop.
  n_updates_ += config_.n_epochs;
  if (logger)
    record_ppo_statistics(*logger, statistics, collector_.buffer(), policy_, n_updates_, lr,
                          clip_range, clip_range_vf);
}

void RecurrentPPO::gather_sequences(int start, int batch) {
  const RolloutBuffer& rollout = collector_.buffer();
  const int n_envs = setup_.n_envs;
  // create_sequencers: a sequence starts at the minibatch's first sample, at an episode start
  // and where the env changes (a sample at step 0).
  std::vector<int> seq_start;  // positions in the minibatch
  for (int j = 0; j < batch; ++j) {
    const int k = flat_[static_cast<size_t>(start + j)];
    if (j == 0 || rollout.episode_starts.data()[k] != 0.0f || k < n_envs) seq_start.push_back(j);
  }
  const Eigen::Index n_seq = static_cast<Eigen::Index>(seq_start.size());
  int max_length = 0;
  for (size_t s = 0; s < seq_start.size(); ++s) {
    const int end = s + 1 < seq_start.size() ? seq_start[s + 1] : batch;
    max_length = std::max(max_length, end - seq_start[s]);
  }
  // pad(): each sequence a column block of the time-major layout, zeros after its end.
  SequenceBatch& b = sequences_;
  b.n_seq = n_seq;
  b.obs.setZero(rollout.obs.rows(), Eigen::Index{max_length} * n_seq);
  b.episode_starts.setZero(Eigen::Index{max_length} * n_seq);
  b.initial = recurrent_.zero_states(n_seq);
  b.sample_columns.resize(static_cast<size_t>(batch));
  mb_act_.resize(policy_.action_dim(), batch);
  for (Eigen::RowVectorXf* v : {&mb_adv_, &mb_ret_, &mb_old_logp_, &mb_old_val_, &values_pred_,
                                &grad_values_, &grad_log_prob_, &grad_entropy_})
    v->resize(batch);
  Eigen::Index s = -1, t = 0;
  for (int j = 0; j < batch; ++j) {
    const int k = flat_[static_cast<size_t>(start + j)];
    if (s + 1 < n_seq && seq_start[static_cast<size_t>(s + 1)] == j) {
      ++s;
      t = 0;
      recurrent_.stored_states(k, b.initial, s);  // the states at the sequence's first step
    }
    const Eigen::Index column = t * n_seq + s;
    rollout.obs.get(k, b.obs.col(column).data());
    b.episode_starts(column) = rollout.episode_starts.data()[k];
    b.sample_columns[static_cast<size_t>(j)] = column;
    mb_act_.col(j) = rollout.actions.col(k);
    mb_adv_(j) = rollout.advantages.data()[k];
    mb_ret_(j) = rollout.returns.data()[k];
    mb_old_logp_(j) = rollout.log_probs.data()[k];
    mb_old_val_(j) = rollout.values.data()[k];
    ++t;
  }
}

void RecurrentPPO::predict(const Eigen::Ref<const Eigen::MatrixXf>& obs, bool deterministic,
                           Eigen::MatrixXf& actions) {
  Eigen::MatrixXf states = Eigen::MatrixXf::Zero(recurrent_state_size(), obs.cols());
  predict_recurrent(obs, Eigen::RowVectorXf::Zero(obs.cols()), states, deterministic, actions);
}

int RecurrentPPO::recurrent_state_size() const {
  return 2 * recurrent_.num_layers() * recurrent_.hidden_size();
}

void RecurrentPPO::predict_recurrent(const Eigen::Ref<const Eigen::MatrixXf>& obs,
                                     const Eigen::Ref<const Eigen::RowVectorXf>& episode_starts,
                                     Eigen::MatrixXf& states, bool deterministic,
                                     Eigen::MatrixXf& actions) {
  const Eigen::Index n = obs.cols(), rows = recurrent_state_size() / 2;
  if (states.rows() != 2 * rows || states.cols() != n || episode_starts.size() != n)
    throw std::invalid_argument("RecurrentPPO: states are " + std::to_string(states.rows()) +
                                " x " + std::to_string(states.cols()) + ", expected " +
                                std::to_string(2 * rows) + " x " + std::to_string(n));
  // The state's rows: the actor's h of every layer, then its c (sb3-contrib's (h, c) pair).
  predict_state_.h = states.topRows(rows);
  predict_state_.c = states.bottomRows(rows);
  recurrent_.predict(obs, episode_starts, predict_state_, action_rng_, deterministic, actions);
  states.topRows(rows) = predict_state_.h;
  states.bottomRows(rows) = predict_state_.c;
  clip_to_box(setup_.action_space, actions);
}

void RecurrentPPO::export_policy(PolicyGraph& graph, const std::string& obs,
                                 bool with_value) const {
  recurrent_.export_to(graph, obs, setup_.action_space, with_value);
  graph.set_action(export_clip_to_box(graph, setup_.action_space, graph.action()));
}

}  // namespace rlrun
