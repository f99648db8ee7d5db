#include "rlrun/algos/crossq/crossq.hpp"

#include "rlrun/algos/common/rng_streams.hpp"
#include "rlrun/core/config_validation.hpp"
#include "rlrun/nn/policy_graph.hpp"

namespace rlrun {

namespace {
void fill_normal(Rng& rng, Eigen::Index rows, Eigen::Index cols, Eigen::MatrixXf& m) {
  m.resize(rows, cols);
  for (Eigen::Index k = 0; k < m.size(); ++k) m.data()[k] = static_cast<float>(rng.normal());
}

// CrossQPolicy: optimizer_kwargs["betas"] = (0.5, 0.999) for Adam ("b1=0.5 is used in the
// original CrossQ implementation"); torch's eps.
constexpr AdamConfig kCrossQAdam{0.5, 0.999, 1e-8};

// What CrossQ adds to SAC's checks (the constructor throws for these too).
ConfigProblems crossq_problems(const CrossQ::Config& config) {
  ConfigProblems out;
  if (config.off_policy.tau != 1.0)
    out.push_back({"tau", "CrossQ has no target networks: sb3-contrib fixes tau at 1.0"});
  if (config.off_policy.batch_size < 2)
    out.push_back({"batch_size", "CrossQ's batch renormalization needs batch_size >= 2"});
  return out;
}
}  // namespace

CrossQNorm CrossQPolicyConfig::norm() const {
  CrossQNorm n;
  n.batch_norm = batch_norm;
  n.options.momentum = static_cast<float>(batch_norm_momentum);
  n.options.eps = static_cast<float>(batch_norm_eps);
  n.options.warmup_steps = renorm_warmup_steps;
  return n;
}

SacActorSde CrossQPolicyConfig::actor_sde(bool use_sde) const {
  SacActorSde sde;
  sde.use_sde = use_sde;
  sde.log_std_init = static_cast<float>(log_std_init);
  sde.full_std = true;  // CrossQPolicy does not pass full_std: the Actor's default
  sde.use_expln = use_expln;
  sde.clip_mean = static_cast<float>(clip_mean);
  return sde;
}

ConfigProblems CrossQ::check(const Config& config, const AlgorithmSetup& setup) {
  ConfigProblems out;
  const CrossQPolicyConfig& p = config.policy;
  // The actor's mean and log std heads, the actor and its acting copy.
  check_box_actor_critic(
      out, setup, config.off_policy,
      {p.net_arch, p.n_critics, 2 * setup.action_space.flat_dim(), 2, 1,
       FeaturesExtractorSettings{FeaturesExtractor::kFlatten, 512, 256, p.normalize_images},
       false});
  const ConfigProblems own = crossq_problems(config);
  out.insert(out.end(), own.begin(), own.end());
  return out;
}

// Weights from the seed itself: the actor (latent_pi, mu, log_std), then the critics (torch's
// default Linear init), as CrossQPolicy._build makes them; the other streams as SAC's.
CrossQ::CrossQ(const Config& config, const AlgorithmSetup& setup)
    : OffPolicyAlgorithm(
          "CrossQ", valid_config(config, "CrossQ").off_policy, setup,
          BoxActionSelection::checked_action_dim(setup, "CrossQ"), {kSampleStream, "sample_rng"},
          encoder_normalizes_images(FeaturesExtractor::kFlatten, config.policy.normalize_images)),
      config_(config),
      action_dim_(setup.action_space.flat_dim()),
      train_rng_(setup.seed ^ kTrainStream),
      predict_rng_(setup.seed ^ kPredictStream),
      actor_(features_dim(), action_dim_, config.policy.net_arch.pi, config.policy.activation_fn,
             config.policy.norm(), config.policy.actor_sde(config.use_sde), setup.pool),
      critic_(features_dim(), action_dim_, config.policy.net_arch.qf, config.policy.activation_fn,
              config.policy.n_critics, config.policy.norm(), setup.pool),
      ent_coef_(config.ent_coef, config.target_entropy, action_dim_),
      acting_(setup, config.action_noise) {
  for (const auto& [key, problem] : crossq_problems(config))
    throw std::invalid_argument("CrossQ: " + key + ": " + problem);
  Rng init_rng(setup.seed);
  actor_.init(init_rng);
  if (config.use_sde) {
    actor_.reset_noise(init_rng, 1);
    acting_actor_.get().reset_noise(init_rng, 1);
  }
  critic_.init(init_rng);
  actor_optimizer_ = Adam(actor_.blocks(), kCrossQAdam);
  for (int i = 0; i < critic_.n_critics(); ++i)
    critic_optimizers_.emplace_back(critic_.q(i).blocks(), kCrossQAdam);
  const auto n_critics = static_cast<size_t>(critic_.n_critics());
  grad_q_.resize(n_critics);
  grad_min_q_.resize(n_critics);
  grad_critic_actions_.resize(n_critics);
  critic_losses_.resize(n_critics);
  // Resume: RNG streams, exploration noise and every Adam's moments (the networks and their
  // BatchRenorm statistics are in the model tensors).
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

void CrossQ::sample_actions(const Eigen::Ref<const Eigen::MatrixXf>& obs, bool training,
                            const Eigen::MatrixXf& noise, Eigen::MatrixXf& actions,
                            Eigen::RowVectorXf& log_prob) {
  if (config_.use_sde)
    actor_.sample(obs, training, train_rng_, actions, log_prob);
  else
    actor_.sample_from_noise(obs, training, noise, actions, log_prob);
}

// sb3-contrib crossq/crossq.py CrossQ.train, one pass of its loop over gradient steps.
CrossQStepStats CrossQ::train_on_batch(const ReplayBatch& b, float lr, bool update_actor) {
  CrossQStepStats stats;
  // "We need to sample because `log_std` may have changed between two gradient steps."
  if (config_.use_sde) actor_.reset_noise(train_rng_, 1);
  // ent_coef = exp(log_ent_coef.detach()), before this step's temperature update.
  const float alpha = ent_coef_.value();
  stats.ent_coef = alpha;
  stats.critic_loss = update_critics(b, alpha, lr);
  // Delayed policy updates: `if self._n_updates % self.policy_delay == 0`.
  if (update_actor) update_actor_and_temperature(b, alpha, lr, stats);
  return stats;
}

double CrossQ::update_critics(const ReplayBatch& b, float alpha, float lr) {
  const Eigen::Index n = b.obs.cols();
  const auto gamma = static_cast<float>(config_.off_policy.gamma);
  // with th.no_grad(): actor.set_bn_training_mode(False)
  //   next_actions, next_log_prob = actor.action_log_prob(next_obs)
  const Eigen::Ref<const Eigen::MatrixXf> next_obs = batch_next_obs(b);
  if (!config_.use_sde) fill_normal(train_rng_, action_dim_, n, next_noise_);
  sample_actions(next_obs, false, next_noise_, next_actions_, next_log_prob_);

  // The joint forward in train mode (critic BN statistics of the obs/next_obs mixture):
  //   all_q_values = cat(critic(cat([obs, next_obs]), cat([actions, next_actions])), dim=1)
  const Eigen::Ref<const Eigen::MatrixXf> obs = batch_obs(b);
  all_obs_.resize(obs.rows(), 2 * n);
  all_obs_ << obs, next_obs;
  all_actions_.resize(action_dim_, 2 * n);
  all_actions_ << b.actions, next_actions_;
  critic_.forward(all_obs_, all_actions_, true);

  // with th.no_grad(): next_q = min over critics (detached) - ent_coef * next_log_prob
  //   target_q = rewards + (1 - dones) * gamma * next_q
  target_q_.resize(1, n);
  for (Eigen::Index j = 0; j < n; ++j) {
    const float next_q = critic_.q(critic_.argmin(n + j)).output()(0, n + j);
    target_q_(0, j) =
        b.rewards(j) + (1.0f - b.dones(j)) * gamma * (next_q - alpha * next_log_prob_(j));
  }

  // critic_loss = 0.5 * sum_i F.mse_loss(current_q_i, target_q): only the first n columns of
  // the joint pass carry a gradient (into both halves' batch statistics); one Adam step.
  const float inv_n = 1.0f / static_cast<float>(n);
  critic_.for_each_critic(2 * n, [&](int i) {
    Eigen::MatrixXf& grad_q = grad_q_[i];
    grad_q.setZero(1, 2 * n);
    grad_q.leftCols(n) = critic_.q(i).output().leftCols(n) - target_q_;
    critic_losses_[i] = static_cast<double>(grad_q.squaredNorm()) * (0.5f * inv_n);
    grad_q *= inv_n;
    critic_.q(i).zero_grad_and_backward(grad_q);
    critic_optimizers_[i].step(lr);
  });
  double loss = 0.0;
  for (double l : critic_losses_) loss += l;
  return loss;
}

void CrossQ::update_actor_and_temperature(const ReplayBatch& b, float alpha, float lr,
                                          CrossQStepStats& stats) {
  const Eigen::Index n = b.obs.cols();
  const float inv_n = 1.0f / static_cast<float>(n);
  stats.actor_updated = true;
  // actor.set_bn_training_mode(True); actions_pi, log_prob = actor.action_log_prob(obs)
  const Eigen::Ref<const Eigen::MatrixXf> obs = batch_obs(b);
  if (!config_.use_sde) fill_normal(train_rng_, action_dim_, n, policy_noise_);
  sample_actions(obs, true, policy_noise_, actions_pi_, log_prob_);

  // The temperature, towards target_entropy (when learned).
  stats.ent_coef_loss = ent_coef_.update(log_prob_, lr);

  // actor_loss = (ent_coef * log_prob - min_i critic_i(obs, actions_pi)).mean(), the critics
  // in eval mode (running statistics) as just stepped.
  critic_.forward(obs, actions_pi_, false);
  q_pi_.resize(n);
  for (Eigen::MatrixXf& g : grad_min_q_) g.setZero(1, n);
  for (Eigen::Index j = 0; j < n; ++j) {
    const int i = critic_.argmin(j);
    q_pi_(j) = critic_.q(i).output()(0, j);
    grad_min_q_[i](0, j) = -inv_n;
  }
  critic_.for_each_critic(
      n, [&](int i) { critic_.action_gradient(i, grad_min_q_[i], grad_critic_actions_[i]); });
  grad_actions_ = grad_critic_actions_[0];
  for (int i = 1; i < critic_.n_critics(); ++i) grad_actions_ += grad_critic_actions_[i];
  double loss = 0.0;
  for (Eigen::Index j = 0; j < n; ++j) loss += static_cast<double>(alpha * log_prob_(j) - q_pi_(j));
  stats.actor_loss = loss * static_cast<double>(inv_n);
  grad_log_prob_.setConstant(n, alpha * inv_n);  // d actor_loss / d log_prob
  actor_.backward(grad_actions_, grad_log_prob_);
  actor_optimizer_.step(lr);
  acting_actor_.invalidate();  // new parameters and running statistics
}

void CrossQ::train(int gradient_steps, Logger* logger) {
  // SB3 _update_learning_rate: the same scheduled lr for the actor, critic and ent_coef.
  const auto lr = static_cast<float>(config_.learning_rate(progress_remaining()));
  CrossQStepStats sum;
  int actor_steps = 0;
  for (int k = 0; k < gradient_steps; ++k) {
    ++n_updates_;  // crossq.py: self._n_updates += 1 before the step
    const CrossQStepStats s =
        train_on_batch(sample_batch(), lr, n_updates_ % config_.policy_delay == 0);
    sum.ent_coef += s.ent_coef;
    sum.critic_loss += s.critic_loss;
    if (!s.actor_updated) continue;
    ++actor_steps;
    sum.actor_loss += s.actor_loss;
    sum.ent_coef_loss += s.ent_coef_loss;
  }
  if (!logger || gradient_steps == 0) return;
  const double n = gradient_steps;
  logger->record("train/n_updates", static_cast<double>(n_updates_));
  logger->record("train/ent_coef", sum.ent_coef / n);
  if (actor_steps > 0) logger->record("train/actor_loss", sum.actor_loss / actor_steps);
  logger->record("train/critic_loss", sum.critic_loss / n);
  if (actor_steps > 0 && ent_coef_.learned())
    logger->record("train/ent_coef_loss", sum.ent_coef_loss / actor_steps);
  logger->record("train/learning_rate", lr);
}

void CrossQ::before_collect_step(int64_t collected_steps) {
  if (config_.use_sde)
    reset_collect_noise(acting_actor_.get(), acting_.action_rng(), setup_.n_envs, collected_steps,
                        config_.sde_sample_freq);
}

void CrossQ::record_rollout_logs(Logger& logger) {
  if (config_.use_sde) logger.record("train/std", actor_.mean_std());
}

void CrossQ::select_actions(const Eigen::MatrixXf& obs, bool warmup, Eigen::MatrixXf& env_actions,
                            Eigen::MatrixXf& buffer_actions) {
  acting_.select(
      obs, warmup && !(config_.use_sde && config_.use_sde_at_warmup),
      [&](Rng& rng, Eigen::MatrixXf& actions) {
        acting_actor_.get().sample(acting_features(obs), false, rng, actions, acting_log_prob_);
      },
      env_actions, buffer_actions);
}

void CrossQ::predict(const Eigen::Ref<const Eigen::MatrixXf>& obs, bool deterministic,
                     Eigen::MatrixXf& actions) {
  if (deterministic)
    acting_actor_.get().mode(acting_features(obs), scaled_actions_);
  else
    acting_actor_.get().sample(acting_features(obs), false, predict_rng_, scaled_actions_,
                               acting_log_prob_);
  acting_.to_env_actions(scaled_actions_, actions);
}

void CrossQ::export_policy(PolicyGraph& graph, const std::string& obs, bool with_value) const {
  const std::string encoded = acting_encoder().export_to(graph, obs);
  const std::string scaled = actor_.export_mode(graph, encoded);
  graph.set_action(acting_.export_env_actions(graph, scaled));
  if (with_value)
    graph.set_value(graph.mlp(graph.concat({encoded, scaled}), critic_.q(0).folded()));
}

void CrossQ::save(TensorMap& tensors) const {
  actor_.save("actor", tensors);
  critic_.save("critic", tensors);
  ent_coef_.save(tensors);
}

void CrossQ::load(const TensorMap& tensors) {
  actor_.load("actor", tensors);
  critic_.load("critic", tensors);
  ent_coef_.load(tensors);
  acting_actor_.invalidate();
}

}  // namespace rlrun
