#include "rlrun/algos/sac/sac.hpp"

#include "rlrun/nn/policy_graph.hpp"

#include <algorithm>
#include <stdexcept>

#include "rlrun/algos/common/rng_streams.hpp"
#include "rlrun/algos/common/training_state.hpp"

namespace rlrun {

namespace {
// Weights use the seed itself; rng_streams.hpp has the acting, noise and replay streams and
// SAC's two more: the actor's reparameterisation noise in updates (kTrainStream), and predict()
// (kPredictStream, so evaluation during training never shifts the training streams).

void fill_normal(Rng& rng, Eigen::Index rows, Eigen::Index cols, Eigen::MatrixXf& m) {
  m.resize(rows, cols);
  for (Eigen::Index k = 0; k < m.size(); ++k) m.data()[k] = static_cast<float>(rng.normal());
}

SacActorSde actor_sde(const SAC::Config& config) {
  SacActorSde sde;
  sde.use_sde = config.use_sde;
  sde.log_std_init = static_cast<float>(config.policy.log_std_init);
  sde.full_std = config.policy.full_std;
  sde.use_expln = config.policy.use_expln;
  sde.clip_mean = static_cast<float>(config.policy.clip_mean);
  return sde;
}
}  // namespace

ConfigProblems SAC::check(const Config& config, const AlgorithmSetup& setup) {
  ConfigProblems out;
  // The actor's mean and log std heads; the actor and its acting copy.
  check_box_actor_critic(out, setup, config.off_policy, config.policy.net_arch,
                         config.policy.n_critics, 2 * setup.action_space.flat_dim(), 2);
  return out;
}

SAC::SAC(const Config& config, const AlgorithmSetup& setup)
    : OffPolicyAlgorithm("SAC", config.off_policy, setup,
                         BoxActionSelection::checked_action_dim(setup, "SAC"),
                         {kSampleStream, "sample_rng"}),
      config_(config),
      action_dim_(setup.action_space.flat_dim()),
      train_rng_(setup.seed ^ kTrainStream),
      predict_rng_(setup.seed ^ kPredictStream),
      actor_(features_dim(), action_dim_, config.policy.net_arch.pi, config.policy.activation_fn,
             actor_sde(config)),
      critic_(features_dim(), action_dim_, config.policy.net_arch.qf, config.policy.activation_fn,
              config.policy.n_critics),
      critic_target_(critic_),
      ent_coef_(config.ent_coef, config.target_entropy, action_dim_),
      acting_(setup, config.action_noise) {
  if (config.target_update_interval < 1)
    throw std::invalid_argument("SAC: target_update_interval must be >= 1");
  // SB3 SACPolicy._build: the actor, then the critics (the targets copies), torch's default
  // Linear init for all; Adam with torch's eps 1e-8 everywhere.
  Rng init_rng(setup.seed);
  actor_.net().init_torch_default(init_rng);
  if (config.use_sde) {
    // proba_distribution_net samples an exploration matrix; the acting copy gets one too.
    actor_.reset_noise(init_rng, 1);
    acting_actor_.get().reset_noise(init_rng, 1);
  }
  critic_.init(init_rng);
  critic_target_ = critic_;
  if (config.use_sde)
    actor_optimizer_ = Adam({actor_.net().block(), actor_.sde().block()});
  else
    actor_optimizer_ = Adam({actor_.net().block()});
  for (int i = 0; i < critic_.n_critics(); ++i)
    critic_optimizers_.emplace_back(std::vector<ParamBlock>{critic_.q(i).net().block()});
  grad_min_q_.resize(critic_.n_critics());
  grad_q_.resize(critic_.n_critics());
  grad_critic_actions_.resize(critic_.n_critics());
  critic_losses_.resize(critic_.n_critics());
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

void SAC::before_collect_step(int64_t collected_steps) {
  if (!config_.use_sde) return;
  // SB3 collect_rollouts: reset_noise(n_envs) when it starts, then, with sde_sample_freq > 0,
  // whenever num_collected_steps % sde_sample_freq == 0 (so twice at the start), from the
  // current log_std (get() refreshes the acting copy).
  SacActor& acting = acting_actor_.get();
  if (collected_steps == 0) acting.reset_noise(acting_.action_rng(), setup_.n_envs);
  if (config_.sde_sample_freq > 0 && collected_steps % config_.sde_sample_freq == 0)
    acting.reset_noise(acting_.action_rng(), setup_.n_envs);
}

void SAC::record_rollout_logs(Logger& logger) {
  if (config_.use_sde) logger.record("train/std", actor_.mean_std());
}

// SB3 sac/sac.py SAC.train, one pass of its loop over gradient steps; CleanRL's
// sac_continuous_action.py has the same update.
EntropyRegularizedStepStats SAC::train_on_batch(const ReplayBatch& b, float lr, bool update_target) {
  const Eigen::Index n = b.obs.cols();
  const float inv_n = 1.0f / static_cast<float>(n);
  const auto gamma = static_cast<float>(config_.off_policy.gamma);
  EntropyRegularizedStepStats stats;
  if (config_.use_sde) {
    // "We need to sample because `log_std` may have changed between two gradient steps":
    // reset_noise() with batch size 1, so the whole minibatch shares one exploration matrix.
    actor_.reset_noise(train_rng_, 1);
  } else {
    // The reparameterisation noise in SB3's order: for the actions at s, then at s'.
    fill_normal(train_rng_, action_dim_, n, policy_noise_);
    fill_normal(train_rng_, action_dim_, n, next_noise_);
  }
  // ent_coef = exp(log_ent_coef.detach()) (or the fixed value): this step uses it as it was
  // before its own update.
  const float alpha = ent_coef_.value();
  stats.ent_coef = alpha;

  // with th.no_grad():
  //   next_actions, next_log_prob = actor.action_log_prob(next_obs)
  //   next_q = min_i critic_target_i(next_obs, next_actions) - ent_coef * next_log_prob
  //   target_q = rewards + (1 - dones) * gamma * next_q
  const Eigen::Ref<const Eigen::MatrixXf> next_obs = batch_next_obs(b);
  if (config_.use_sde)
    actor_.sample(next_obs, train_rng_, next_actions_, next_log_prob_);
  else
    actor_.sample_from_noise(next_obs, next_noise_, next_actions_, next_log_prob_);
  critic_target_.forward(next_obs, next_actions_);
  target_q_.resize(1, n);
  for (Eigen::Index j = 0; j < n; ++j) {
    const float next_q = critic_target_.min(j) - alpha * next_log_prob_(j);
    target_q_(0, j) = b.rewards(j) + (1.0f - b.dones(j)) * gamma * next_q;
  }

  // actions_pi, log_prob = actor.action_log_prob(obs). SB3 samples these first; here s' went
  // first because the actor keeps only its last forward pass for the backward below (the
  // noise was drawn in SB3's order, so the numbers are the same).
  const Eigen::Ref<const Eigen::MatrixXf> obs = batch_obs(b);
  if (config_.use_sde)
    actor_.sample(obs, train_rng_, actions_pi_, log_prob_);
  else
    actor_.sample_from_noise(obs, policy_noise_, actions_pi_, log_prob_);

  // ent_coef_loss = -(log_ent_coef * (log_prob + target_entropy).detach()).mean(); one Adam
  // step on log_ent_coef, whose gradient is -mean(log_prob + target_entropy).
  if (ent_coef_.learned()) {
    const double shifted = static_cast<double>(log_prob_.mean()) + ent_coef_.target_entropy();
    stats.ent_coef_loss = -static_cast<double>(ent_coef_.log_value()) * shifted;
    ent_coef_.log_ent_coef().grad(0) = static_cast<float>(-shifted);
    ent_coef_.optimizer().step(lr);
  }

  // critic_loss = 0.5 * sum_i F.mse_loss(critic_i(obs, actions), target_q); one Adam step.
  // The critics are independent here: each one's loss, backward and Adam step may run on its
  // own core (ContinuousCritic::for_each_critic); the losses are summed in critic order.
  critic_.forward(obs, b.actions);
  critic_.for_each_critic(n, [&](int i) {
    Eigen::MatrixXf& grad_q = grad_q_[i];
    grad_q = critic_.q(i).output() - target_q_;
    critic_losses_[i] = static_cast<double>(grad_q.squaredNorm()) * (0.5f * inv_n);
    grad_q *= inv_n;  // d critic_loss / d Q_i = (Q_i - target_q) / n
    critic_.q(i).zero_grad_and_backward(grad_q);
    critic_optimizers_[i].step(lr);
  });
  for (double loss : critic_losses_) stats.critic_loss += loss;

  // actor_loss = (ent_coef * log_prob - min_i critic_i(obs, actions_pi)).mean(), through the
  // critics as just stepped and pathwise through the squashed Gaussian; one Adam step.
  critic_.forward(obs, actions_pi_);
  for (Eigen::MatrixXf& g : grad_min_q_) g.setZero(1, n);
  grad_log_prob_.setConstant(n, alpha * inv_n);
  double actor_loss = 0.0;
  for (Eigen::Index j = 0; j < n; ++j) {
    grad_min_q_[critic_.argmin(j)](0, j) = -inv_n;
    actor_loss += static_cast<double>(alpha * log_prob_(j) - critic_.min(j));
  }
  stats.actor_loss = actor_loss * static_cast<double>(inv_n);
  critic_.for_each_critic(n, [&](int i) {
    critic_.action_gradient(i, grad_min_q_[i], grad_critic_actions_[i]);
  });
  grad_actions_ = grad_critic_actions_[0];
  for (int i = 1; i < critic_.n_critics(); ++i) grad_actions_ += grad_critic_actions_[i];
  actor_.backward(grad_actions_, grad_log_prob_);
  actor_optimizer_.step(lr);
  acting_actor_.invalidate();

  // polyak_update(critic.parameters(), critic_target.parameters(), tau)
  if (update_target)
    polyak_update(critic_, critic_target_, static_cast<float>(config_.off_policy.tau));
  return stats;
}

void SAC::train(int gradient_steps, Logger* logger) {
  // SB3 _update_learning_rate: the same scheduled lr for actor, critic and ent_coef optimizers.
  const auto lr = static_cast<float>(config_.learning_rate(progress_remaining()));
  train_entropy_regularized(gradient_steps, config_.target_update_interval, lr, ent_coef_.learned(),
                            n_updates_, logger, [&](bool update_target) {
                              return train_on_batch(sample_batch(), lr, update_target);
                            });
}

void SAC::select_actions(const Eigen::MatrixXf& obs, bool warmup, Eigen::MatrixXf& env_actions,
                         Eigen::MatrixXf& buffer_actions) {
  // SB3 _sample_action: uniform samples before learning_starts unless gSDE acts at warmup.
  acting_.select(
      obs, warmup && !(config_.use_sde && config_.use_sde_at_warmup),
      [&](Rng& rng, Eigen::MatrixXf& actions) {
        // A stochastic sample of the policy (SB3 predict with deterministic=False).
        acting_actor_.get().sample(acting_features(obs), rng, actions, acting_log_prob_);
      },
      env_actions, buffer_actions);
}

// predict(deterministic): the squashed mean unscaled to the Box; the value is the first
// critic's Q(s, a) of that action.
void SAC::export_policy(PolicyGraph& graph, const std::string& obs, bool with_value) const {
  const std::string features = acting_encoder().export_to(graph, obs);
  const std::string scaled = actor_.export_mode(graph, features);
  graph.set_action(acting_.export_env_actions(graph, scaled));
  if (with_value) graph.set_value(graph.mlp(graph.concat({features, scaled}), critic_.q(0).net()));
}

void SAC::predict(const Eigen::Ref<const Eigen::MatrixXf>& obs, bool deterministic,
                  Eigen::MatrixXf& actions) {
  if (deterministic)
    acting_actor_.get().mode(acting_features(obs), scaled_actions_);
  else
    acting_actor_.get().sample(acting_features(obs), predict_rng_, scaled_actions_,
                                acting_log_prob_);
  acting_.to_env_actions(scaled_actions_, actions);
}

void SAC::save(TensorMap& tensors) const {
  actor_.save("actor", tensors);
  critic_.save("critic", tensors);
  critic_target_.save("critic_target", tensors);
  ent_coef_.save(tensors);
}

void SAC::load(const TensorMap& tensors) {
  actor_.load("actor", tensors);
  critic_.load("critic", tensors);
  critic_target_.load("critic_target", tensors);
  ent_coef_.load(tensors);
  acting_actor_.invalidate();
}

}  // namespace rlrun
