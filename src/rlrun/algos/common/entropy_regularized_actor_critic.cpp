#include "rlrun/algos/common/entropy_regularized_actor_critic.hpp"

#include "rlrun/algos/common/rng_streams.hpp"
#include "rlrun/nn/policy_graph.hpp"

namespace rlrun {

namespace {
void fill_normal(Rng& rng, Eigen::Index rows, Eigen::Index cols, Eigen::MatrixXf& m) {
  m.resize(rows, cols);
  for (Eigen::Index k = 0; k < m.size(); ++k) m.data()[k] = static_cast<float>(rng.normal());
}
}  // namespace

SacActorSde EntropyRegularizedPolicyConfig::actor_sde(bool use_sde) const {
  SacActorSde sde;
  sde.use_sde = use_sde;
  sde.log_std_init = static_cast<float>(log_std_init);
  sde.full_std = full_std;
  sde.use_expln = use_expln;
  sde.clip_mean = static_cast<float>(clip_mean);
  return sde;
}

// Weights use the seed itself; rng_streams.hpp has the acting, noise and replay streams and two
// more: the actor's reparameterisation noise in updates (kTrainStream), and predict()
// (kPredictStream, so evaluation during training never shifts the training streams). SAC and
// TQC use the same ones, so runs of both with one seed start from the same draws.
EntropyRegularizedActorCritic::EntropyRegularizedActorCritic(
    const std::string& id, const EntropyRegularizedConfig& config,
    const EntropyRegularizedPolicyConfig& policy, const AlgorithmSetup& setup, int critic_outputs)
    : OffPolicyAlgorithm(
          id, config.off_policy, setup, BoxActionSelection::checked_action_dim(setup, id),
          {kSampleStream, "sample_rng"},
          encoder_normalizes_images(policy.features_extractor_class, policy.normalize_images)),
      config_(config),
      action_dim_(setup.action_space.flat_dim()),
      critic_(FeaturesExtractorNet(policy.extractor(), setup.observation_space, features_dim(),
                                   setup.pool),
              action_dim_, policy.net_arch.qf, policy.activation_fn, policy.n_critics,
              critic_outputs, setup.pool),
      critic_target_(critic_),
      ent_coef_(config.ent_coef, config.target_entropy, action_dim_),
      train_rng_(setup.seed ^ kTrainStream),
      predict_rng_(setup.seed ^ kPredictStream),
      actor_(FeaturesExtractorNet(policy.extractor(), setup.observation_space, features_dim(),
                                  setup.pool),
             action_dim_, policy.net_arch.pi, policy.activation_fn,
             policy.actor_sde(config.use_sde), setup.pool),
      acting_(setup, config.action_noise) {
  // SB3 SACPolicy._build (sb3-contrib TQCPolicy._build alike): the actor, then the critics (the
  // targets copies), torch's default Linear init for all; Adam with torch's eps 1e-8 everywhere.
  Rng init_rng(setup.seed);
  actor_.net().init_torch_default(init_rng);
  if (config.use_sde) {
    // proba_distribution_net samples an exploration matrix; the acting copy gets one too.
    actor_.reset_noise(init_rng, 1);
    acting_actor_.get().reset_noise(init_rng, 1);
  }
  critic_.init(init_rng);
  // CnnPolicy: make_features_extractor for the actor, then for the critic (torch's default
  // init), from a stream of their own so that the heads' initial weights stay those of the
  // same run without a CNN; critic_target copies the critic, its CNN included.
  Rng extractor_rng(setup.seed ^ kFeaturesExtractorInitStream);
  actor_.features_extractor().init_torch_default(extractor_rng);
  if (policy.share_features_extractor && actor_.features_extractor().learned()) {
    // SB3 SACPolicy._build with share_features_extractor: the critic reads the actor's
    // extractor (not trained by the critic loss); critic_target gets its own copy of it,
    // which Polyak averaging then moves towards the actor's.
    critic_.share_features_extractor(actor_.features_extractor());
  } else {
    critic_.features_extractor().init_torch_default(extractor_rng);
  }
  critic_target_ = critic_;
  critic_target_.own_features_extractor_copy();
  if (config.use_sde)
    actor_optimizer_ = Adam({actor_.net().block(), actor_.sde().block()});
  else
    actor_optimizer_ = Adam({actor_.net().block()});
  for (int i = 0; i < critic_.n_critics(); ++i)
    critic_optimizers_.emplace_back(std::vector<ParamBlock>{critic_.q(i).net().block()});
  extractor_optimizers_ = ExtractorOptimizers(
      actor_.features_extractor(),
      critic_.owns_features_extractor() ? &critic_.features_extractor() : nullptr, setup.pool);
  if (extractor_optimizers_.active()) checkpoint("extractor_optimizers", extractor_optimizers_);
  // Resume: RNG streams, exploration noise and every Adam's moments (the networks, targets
  // included, are in the model tensors).
  checkpoint("train_rng", train_rng_);
  checkpoint("predict_rng", predict_rng_);
  checkpoint("acting", acting_);
  checkpoint("actor_optimizer", actor_optimizer_);
  for (int i = 0; i < critic_.n_critics(); ++i)
    checkpoint("critic_optimizer" + std::to_string(i), critic_optimizers_[i]);
  checkpoint("ent_coef", ent_coef_);
  if (config.use_sde) {
    checkpoint("actor_noise", actor_);
    checkpoint("acting_actor_noise", acting_actor_.get());
  }
}

float EntropyRegularizedActorCritic::begin_step(Eigen::Index n) {
  if (config_.use_sde) {
    actor_.reset_noise(train_rng_, 1);  // one exploration matrix for the whole minibatch
  } else {
    fill_normal(train_rng_, action_dim_, n, policy_noise_);
    fill_normal(train_rng_, action_dim_, n, next_noise_);
  }
  return ent_coef_.value();
}

void EntropyRegularizedActorCritic::sample_actions(const Eigen::Ref<const Eigen::MatrixXf>& obs,
                                                   const Eigen::MatrixXf& noise,
                                                   Eigen::MatrixXf& actions,
                                                   Eigen::RowVectorXf& log_prob) {
  if (config_.use_sde)
    actor_.sample(obs, train_rng_, actions, log_prob);
  else
    actor_.sample_from_noise(obs, noise, actions, log_prob);
}

void EntropyRegularizedActorCritic::sample_next_actions(
    const Eigen::Ref<const Eigen::MatrixXf>& next_obs) {
  sample_actions(next_obs, next_noise_, next_actions_, next_log_prob_);
}

void EntropyRegularizedActorCritic::sample_policy_actions(
    const Eigen::Ref<const Eigen::MatrixXf>& obs) {
  sample_actions(obs, policy_noise_, actions_pi_, log_prob_);
}

double EntropyRegularizedActorCritic::update_actor(const Eigen::RowVectorXf& q_pi,
                                                   const Eigen::MatrixXf& grad_actions, float alpha,
                                                   float lr) {
  const Eigen::Index n = q_pi.size();
  const float inv_n = 1.0f / static_cast<float>(n);
  double loss = 0.0;
  for (Eigen::Index j = 0; j < n; ++j) loss += static_cast<double>(alpha * log_prob_(j) - q_pi(j));
  grad_log_prob_.setConstant(n, alpha * inv_n);  // d actor_loss / d log_prob
  actor_.backward(grad_actions, grad_log_prob_);
  actor_optimizer_.step(lr);
  extractor_optimizers_.step_actor(lr);
  acting_actor_.invalidate();
  return loss * static_cast<double>(inv_n);
}

void EntropyRegularizedActorCritic::update_critic_features_extractor(float lr) {
  critic_.backward_features_extractor();
  extractor_optimizers_.step_critic(lr);
}

void EntropyRegularizedActorCritic::update_target_critics() {
  polyak_update(critic_, critic_target_, static_cast<float>(config_.off_policy.tau));
}

void EntropyRegularizedActorCritic::train(int gradient_steps, Logger* logger) {
  // SB3 _update_learning_rate: the same scheduled lr for the actor, critic and ent_coef
  // optimizers.
  const auto lr = static_cast<float>(config_.learning_rate(progress_remaining()));
  EntropyRegularizedStepStats sum;
  for (int k = 0; k < gradient_steps; ++k) {
    const EntropyRegularizedStepStats s =
        train_on_batch(sample_batch(), lr, k % config_.target_update_interval == 0);
    sum.ent_coef += s.ent_coef;
    sum.ent_coef_loss += s.ent_coef_loss;
    sum.actor_loss += s.actor_loss;
    sum.critic_loss += s.critic_loss;
  }
  n_updates_ += gradient_steps;
  if (!logger || gradient_steps == 0) return;
  const double n = gradient_steps;
  logger->record("train/n_updates", static_cast<double>(n_updates_));
  logger->record("train/ent_coef", sum.ent_coef / n);
  logger->record("train/actor_loss", sum.actor_loss / n);
  logger->record("train/critic_loss", sum.critic_loss / n);
  if (ent_coef_.learned()) logger->record("train/ent_coef_loss", sum.ent_coef_loss / n);
  logger->record("train/learning_rate", lr);
}

void EntropyRegularizedActorCritic::before_collect_step(int64_t collected_steps) {
  // get() refreshes the acting copy: the noise comes from the current log_std.
  if (config_.use_sde)
    reset_collect_noise(acting_actor_.get(), acting_.action_rng(), setup_.n_envs, collected_steps,
                        config_.sde_sample_freq);
}

void EntropyRegularizedActorCritic::record_rollout_logs(Logger& logger) {
  if (config_.use_sde) logger.record("train/std", actor_.mean_std());
}

void EntropyRegularizedActorCritic::select_actions(const Eigen::MatrixXf& obs, bool warmup,
                                                   Eigen::MatrixXf& env_actions,
                                                   Eigen::MatrixXf& buffer_actions) {
  acting_.select(
      obs, warmup && !(config_.use_sde && config_.use_sde_at_warmup),
      [&](Rng& rng, Eigen::MatrixXf& actions) {
        // A stochastic sample of the policy (SB3 predict with deterministic=False).
        acting_actor_.get().sample(acting_features(obs), rng, actions, acting_log_prob_);
      },
      env_actions, buffer_actions);
}

EntropyRegularizedActorCritic::ExportedAction EntropyRegularizedActorCritic::export_action(
    PolicyGraph& graph, const std::string& obs) const {
  const std::string encoded = acting_encoder().export_to(graph, obs);
  const std::string scaled =
      actor_.export_mode(graph, actor_.features_extractor().export_to(graph, encoded));
  graph.set_action(acting_.export_env_actions(graph, scaled));
  return {encoded, scaled};
}

std::string EntropyRegularizedActorCritic::export_critic_input(PolicyGraph& graph,
                                                               const ExportedAction& action) const {
  return graph.concat(
      {critic_.features_extractor().export_to(graph, action.encoded), action.scaled});
}

void EntropyRegularizedActorCritic::predict(const Eigen::Ref<const Eigen::MatrixXf>& obs,
                                            bool deterministic, Eigen::MatrixXf& actions) {
  if (deterministic)
    acting_actor_.get().mode(acting_features(obs), scaled_actions_);
  else
    acting_actor_.get().sample(acting_features(obs), predict_rng_, scaled_actions_,
                               acting_log_prob_);
  acting_.to_env_actions(scaled_actions_, actions);
}

void EntropyRegularizedActorCritic::save(TensorMap& tensors) const {
  actor_.save("actor", tensors);
  critic_.save("critic", tensors);
  critic_target_.save("critic_target", tensors);
  ent_coef_.save(tensors);
}

void EntropyRegularizedActorCritic::load(const TensorMap& tensors) {
  actor_.load("actor", tensors);
  critic_.load("critic", tensors);
  critic_target_.load("critic_target", tensors);
  ent_coef_.load(tensors);
  acting_actor_.invalidate();
}

}  // namespace rlrun
