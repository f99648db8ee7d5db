#include "rlrun/algos/td3/td3.hpp"

#include "rlrun/nn/policy_graph.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>
#include <utility>

#include "rlrun/algos/common/polyak.hpp"
#include "rlrun/algos/common/rng_streams.hpp"
#include "rlrun/algos/common/training_state.hpp"
#include "rlrun/core/config_validation.hpp"

namespace rlrun {

namespace {
// Weights use the seed itself; rng_streams.hpp has the acting, noise and replay streams.
constexpr uint64_t kSmoothingStream = 0xc2b2ae3d27d4eb4fULL;  // target policy smoothing noise

// Logger keys built once (the logger takes std::string; these outgrow the small-string buffer).
const std::string kKeyNUpdates = "train/n_updates";
const std::string kKeyActorLoss = "train/actor_loss";
const std::string kKeyCriticLoss = "train/critic_loss";
const std::string kKeyLearningRate = "train/learning_rate";
}  // namespace

ConfigProblems TD3::check(const Config& config, const AlgorithmSetup& setup) {
  ConfigProblems out;
  // The actor, its target, its acting copy and the second core's activations.
  const Td3PolicyConfig& p = config.policy;
  check_box_actor_critic(out, setup, config.off_policy,
                         {p.net_arch, p.n_critics, setup.action_space.flat_dim(), 4, 1,
                          p.extractor(), p.share_features_extractor});
  return out;
}

TD3::TD3(const Config& config, const AlgorithmSetup& setup, std::string id)
    : OffPolicyAlgorithm(id, valid_config(config, id).off_policy, setup,
                         BoxActionSelection::checked_action_dim(setup, id),
                         {kSampleStream, "sample_rng"},
                         encoder_normalizes_images(config.policy.features_extractor_class,
                                                   config.policy.normalize_images)),
      config_(config),
      action_dim_(setup.action_space.flat_dim()),
      smoothing_rng_(setup.seed ^ kSmoothingStream),
      actor_(FeaturesExtractorNet(config.policy.extractor(), setup.observation_space,
                                  features_dim(), setup.pool),
             action_dim_, config.policy.net_arch.pi, config.policy.activation_fn, setup.pool),
      actor_target_(actor_),
      critic_(FeaturesExtractorNet(config.policy.extractor(), setup.observation_space,
                                   features_dim(), setup.pool),
              action_dim_, config.policy.net_arch.qf, config.policy.activation_fn,
              config.policy.n_critics, /*n_outputs=*/1, setup.pool),
      critic_target_(critic_),
      acting_(setup, config.action_noise) {
  // SB3 TD3Policy._build: the actor (its target a copy), then the critics (targets copies);
  // torch's default Linear init; Adam with torch's defaults (eps 1e-8) for actor and critics.
  Rng init_rng(setup.seed);
  actor_.net().init_torch_default(init_rng);
  critic_.init(init_rng);
  // CnnPolicy: the actor's and the critic's NatureCNN (torch's default init) from a stream of
  // their own, so that the heads start as without a CNN; the targets copy them.
  Rng extractor_rng(setup.seed ^ kFeaturesExtractorInitStream);
  actor_.features_extractor().init_torch_default(extractor_rng);
  const bool share =
      config.policy.share_features_extractor && actor_.features_extractor().learned();
  if (!share) critic_.features_extractor().init_torch_default(extractor_rng);
  actor_target_ = actor_;
  if (share) {
    // SB3 TD3Policy._build with share_features_extractor: the critic reads the actor's
    // extractor, critic_target the actor target's ("the effective polyak coefficient for the
    // features extractor will be 2 * tau": both target updates below move it).
    critic_.share_features_extractor(actor_.features_extractor());
    critic_target_ = critic_;
    critic_target_.share_features_extractor(actor_target_.features_extractor());
  } else {
    critic_target_ = critic_;
  }
  actor_optimizer_ = Adam({actor_.net().block()});
  for (int i = 0; i < critic_.n_critics(); ++i)
    critic_optimizers_.emplace_back(std::vector<ParamBlock>{critic_.q(i).net().block()});
  extractor_optimizers_ = ExtractorOptimizers(
      actor_.features_extractor(),
      critic_.owns_features_extractor() ? &critic_.features_extractor() : nullptr, setup.pool);
  if (extractor_optimizers_.active()) checkpoint("extractor_optimizers", extractor_optimizers_);
  critic_grad_q_.resize(critic_.n_critics());
  critic_losses_.resize(critic_.n_critics());
  // Resume: RNG streams, exploration noise and every Adam's moments (the networks, targets
  // included, are in the model tensors).
  checkpoint("smoothing_rng", smoothing_rng_);
  checkpoint("acting", acting_);
  checkpoint("actor_optimizer", actor_optimizer_);
  for (int i = 0; i < critic_.n_critics(); ++i)
    checkpoint("critic_optimizer" + std::to_string(i), critic_optimizers_[i]);
}

// SB3 td3/td3.py TD3.train, one pass of its loop over gradient steps; CleanRL's
// td3_continuous_action.py has the same update (policy_frequency is policy_delay).
Td3StepStats TD3::train_on_batch(const ReplayBatch& b, float lr) {
  const Eigen::Index n = b.obs.cols();
  const float inv_n = 1.0f / static_cast<float>(n);
  const auto gamma = static_cast<float>(config_.off_policy.gamma);
  ++n_updates_;
  Td3StepStats stats;

  // with th.no_grad():
  //   noise = N(0, target_policy_noise).clamp(-target_noise_clip, target_noise_clip)
  //   next_actions = (actor_target(next_obs) + noise).clamp(-1, 1)
  //   next_q = min_i critic_target_i(next_obs, next_actions)
  //   target_q = rewards + (1 - dones) * gamma * next_q
  const auto noise_std = static_cast<float>(config_.target_policy_noise);
  const auto noise_clip = static_cast<float>(config_.target_noise_clip);
  smoothing_noise_.resize(action_dim_, n);
  if (noise_std == 0.0f || noise_clip == 0.0f) {
    smoothing_noise_.setZero();  // DDPG's clip 0 zeroes whatever was drawn: draw nothing
  } else {
    for (Eigen::Index k = 0; k < smoothing_noise_.size(); ++k)
      smoothing_noise_(k) = std::clamp(noise_std * static_cast<float>(smoothing_rng_.normal()),
                                       -noise_clip, noise_clip);
  }
  const Eigen::Ref<const Eigen::MatrixXf> next_obs = batch_next_obs(b);
  next_actions_ =
      (actor_target_.forward(next_obs) + smoothing_noise_).cwiseMax(-1.0f).cwiseMin(1.0f);
  critic_target_.forward(next_obs, next_actions_);
  target_q_.resize(1, n);
  for (Eigen::Index j = 0; j < n; ++j)
    target_q_(0, j) = b.rewards(j) + ((1.0f - b.dones(j)) * gamma) * critic_target_.min(j);

  // critic_loss = sum_i F.mse_loss(critic_i(obs, actions), target_q); one Adam step.
  const Eigen::Ref<const Eigen::MatrixXf> obs = batch_obs(b);
  // Each critic's loss, backward and Adam step may run on its own core
  // (ContinuousCritic::for_each_critic); the losses are summed in critic order.
  critic_.forward(obs, b.actions);
  critic_.for_each_critic(n, [&](int i) {
    Eigen::MatrixXf& grad_q = critic_grad_q_[i];
    grad_q = critic_.q(i).output() - target_q_;
    critic_losses_[i] = static_cast<double>(grad_q.squaredNorm()) * inv_n;
    grad_q *= 2.0f * inv_n;  // d critic_loss / d Q_i = 2 (Q_i - target_q) / n
    critic_.zero_grad_and_backward(i, grad_q);
    critic_optimizers_[i].step(lr);
  });
  for (double loss : critic_losses_) stats.critic_loss += loss;
  // CnnPolicy: the critic's NatureCNN learns from the same loss (SB3's critic optimizer).
  critic_.backward_features_extractor();
  extractor_optimizers_.step_critic(lr);

  // Delayed policy updates: `if self._n_updates % self.policy_delay == 0`.
  if (n_updates_ % config_.policy_delay != 0) return stats;
  // actor_loss = -critic.q1_forward(obs, actor(obs)).mean(), through critic 1 into the actor
  // (q1_forward takes the critic's CNN features without gradient); one Adam step.
  const Eigen::MatrixXf& q1 = critic_.q1_forward(obs, actor_.forward(obs));
  stats.actor_loss = -static_cast<double>(q1.sum()) * inv_n;
  stats.actor_updated = true;
  grad_q_.setConstant(1, n, -inv_n);
  critic_.action_gradient(0, grad_q_, grad_actions_);
  actor_.backward(grad_actions_);
  actor_optimizer_.step(lr);
  extractor_optimizers_.step_actor(lr);
  acting_actor_.invalidate();

  // polyak_update(critic.parameters(), critic_target.parameters(), tau), the same for the actor.
  const auto tau = static_cast<float>(config_.off_policy.tau);
  polyak_update(critic_, critic_target_, tau);
  polyak_update(actor_, actor_target_, tau);
  return stats;
}

void TD3::train(int gradient_steps, Logger* logger) {
  // SB3 _update_learning_rate: one scheduled lr for the actor and critic optimizers.
  const auto lr = static_cast<float>(config_.learning_rate(progress_remaining()));
  double critic_loss_sum = 0.0, actor_loss_sum = 0.0;
  int actor_updates = 0;
  for (int step = 0; step < gradient_steps; ++step) {
    const Td3StepStats s = train_on_batch(sample_batch(), lr);
    critic_loss_sum += s.critic_loss;
    if (s.actor_updated) {
      actor_loss_sum += s.actor_loss;
      ++actor_updates;
    }
  }
  if (!logger || gradient_steps == 0) return;
  logger->record(kKeyLearningRate, lr);
  logger->record(kKeyNUpdates, static_cast<double>(n_updates_));
  if (actor_updates > 0) logger->record(kKeyActorLoss, actor_loss_sum / actor_updates);
  logger->record(kKeyCriticLoss, critic_loss_sum / gradient_steps);
}

void TD3::select_actions(const Eigen::MatrixXf& obs, bool warmup, Eigen::MatrixXf& env_actions,
                         Eigen::MatrixXf& buffer_actions) {
  // SB3 predicts (actor, unscaled to the bounds) and scales back to [-1, 1]; the actor's tanh
  // output is that scaled action already.
  acting_.select(
      obs, warmup,
      [&](Rng&, Eigen::MatrixXf& actions) {
        actions = acting_actor_.get().forward(acting_features(obs));
      },
      env_actions, buffer_actions);
}

// predict(): tanh(mu(obs)) unscaled to the Box; the value is the first critic's Q(s, a).
void TD3::export_policy(PolicyGraph& graph, const std::string& obs, bool with_value) const {
  const std::string encoded = acting_encoder().export_to(graph, obs);
  const std::string scaled = graph.activation(
      graph.mlp(actor_.features_extractor().export_to(graph, encoded), actor_.net()),
      Activation::kTanh);
  graph.set_action(acting_.export_env_actions(graph, scaled));
  if (with_value) {
    const std::string features = critic_.features_extractor().export_to(graph, encoded);
    graph.set_value(graph.mlp(graph.concat({features, scaled}), critic_.q(0).net()));
  }
}

void TD3::predict(const Eigen::Ref<const Eigen::MatrixXf>& obs, bool /*deterministic*/,
                  Eigen::MatrixXf& actions) {
  acting_.to_env_actions(acting_actor_.get().forward(acting_features(obs)), actions);
}

void TD3::save(TensorMap& tensors) const {
  actor_.save("actor", tensors);
  actor_target_.save("actor_target", tensors);
  critic_.save("critic", tensors);
  critic_target_.save("critic_target", tensors);
}

void TD3::load(const TensorMap& tensors) {
  actor_.load("actor", tensors);
  actor_target_.load("actor_target", tensors);
  critic_.load("critic", tensors);
  critic_target_.load("critic_target", tensors);
  acting_actor_.invalidate();
}

}  // namespace rlrun
