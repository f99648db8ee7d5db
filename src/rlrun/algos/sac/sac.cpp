#include "rlrun/algos/sac/sac.hpp"

#include <algorithm>
#include <cmath>
#include <span>
#include <stdexcept>

#include "rlrun/algos/common/action_scaling.hpp"
#include "rlrun/algos/sac/sac_loss.hpp"
#include "rlrun/env/vec_env.hpp"

namespace rlrun {

namespace {
// Distinct streams from one seed: weights, acting, exploration noise, replay sampling, the
// actor's reparameterisation noise in updates, and predict() (so evaluation during training
// never shifts the training streams).
constexpr uint64_t kActionStream = 0x5851f42d4c957f2dULL;
constexpr uint64_t kNoiseStream = 0x2545f4914f6cdd1dULL;
constexpr uint64_t kSampleStream = 0x14057b7ef767814fULL;
constexpr uint64_t kTrainStream = 0x9e3779b97f4a7c15ULL;
constexpr uint64_t kPredictStream = 0xda942042e4dd58b5ULL;

int checked_action_dim(const AlgorithmSetup& setup) {
  if (!setup.observation_space.is_box())
    throw std::invalid_argument("SAC: observation space " + setup.observation_space.describe() +
                                " is not supported (Box only)");
  const Space& a = setup.action_space;
  if (!a.is_box())
    throw std::invalid_argument(
        "SAC: action space " + a.describe() +
        " is not supported (Box only; wrap Discrete envs with DiscreteAsBox)");
  for (size_t i = 0; i < a.low().size(); ++i)
    if (!std::isfinite(a.low()[i]) || !std::isfinite(a.high()[i]) || !(a.low()[i] < a.high()[i]))
      throw std::invalid_argument(
          "SAC: the action space " + a.describe() +
          " must have finite bounds low < high (actions are squashed by tanh)");
  return a.flat_dim();
}

const SAC::Config& checked(const SAC::Config& c) {
  const OffPolicyConfig& o = c.off_policy;
  if (o.batch_size < 1) throw std::invalid_argument("SAC: batch_size must be >= 1");
  if (o.buffer_size < 1) throw std::invalid_argument("SAC: buffer_size must be >= 1");
  if (!(o.tau >= 0.0 && o.tau <= 1.0)) throw std::invalid_argument("SAC: tau must be in [0, 1]");
  if (c.target_update_interval < 1)
    throw std::invalid_argument("SAC: target_update_interval must be >= 1");
  if (c.policy.n_critics < 1) throw std::invalid_argument("SAC: policy.n_critics must be >= 1");
  return c;
}

void fill_normal(Rng& rng, Eigen::MatrixXf& m) {
  for (Eigen::Index k = 0; k < m.size(); ++k) m.data()[k] = static_cast<float>(rng.normal());
}
}  // namespace

SAC::SAC(const Config& config, const AlgorithmSetup& setup)
    : config_(checked(config)),
      setup_(setup),
      obs_dim_(setup.observation_space.flat_dim()),
      action_dim_(checked_action_dim(setup)),
      init_rng_(setup.seed),
      action_rng_(setup.seed ^ kActionStream),
      noise_rng_(setup.seed ^ kNoiseStream),
      sample_rng_(setup.seed ^ kSampleStream),
      train_rng_(setup.seed ^ kTrainStream),
      predict_rng_(setup.seed ^ kPredictStream),
      actor_(obs_dim_, action_dim_, config.policy.net_arch,
             parse_activation(config.policy.activation_fn)),
      ent_coef_(config.ent_coef, config.target_entropy, action_dim_),
      action_noise_(config.action_noise, action_dim_, setup.n_envs) {
  const Activation act = parse_activation(config_.policy.activation_fn);
  // SB3 SACPolicy._build: actor first, then the critics; torch's default Linear init for all
  // (off-policy policies never call init_weights). Adam with torch's eps 1e-8 everywhere.
  actor_.net().init_torch_default(init_rng_);
  actor_optimizer_ = Adam({actor_.net().block()});
  critics_.reserve(config_.policy.n_critics);
  for (int i = 0; i < config_.policy.n_critics; ++i)
    critics_.emplace_back(obs_dim_ + action_dim_, config_.policy.net_arch, act, init_rng_);
  acting_actor_ = actor_;

  grad_q_.resize(critics_.size());
  critic_losses_.resize(critics_.size());
  for (const SacCritic& c : critics_) {
    target_values_.push_back(&c.target_values());
    q_values_.push_back(&c.values());
  }
  resize_workspaces(config_.off_policy.batch_size);
}

void SAC::resize_workspaces(Eigen::Index batch) {
  for (Eigen::MatrixXf* m :
       {&policy_noise_, &next_noise_, &actions_pi_, &next_actions_, &grad_actions_})
    m->resize(action_dim_, batch);
  for (Eigen::RowVectorXf* v : {&log_prob_, &next_log_prob_, &grad_log_prob_}) v->resize(batch);
  for (Eigen::MatrixXf* m : {&obs_action_, &next_obs_action_, &obs_action_pi_})
    m->resize(obs_dim_ + action_dim_, batch);
  target_q_.resize(1, batch);
  for (Eigen::MatrixXf& g : grad_q_) g.resize(1, batch);
}

void SAC::sync_acting_actor() {
  if (!acting_stale_) return;
  acting_actor_.net().params() = actor_.net().params();
  acting_stale_ = false;
}

void SAC::to_env_actions(const Eigen::MatrixXf& scaled, Eigen::MatrixXf& env_actions) const {
  // SB3 unscale_action: low + 0.5 (a + 1)(high - low); clamped so that rounding at a = +-1
  // never leaves the Box.
  unscale_actions(setup_.action_space, scaled, env_actions);
  const Space& space = setup_.action_space;
  for (Eigen::Index j = 0; j < env_actions.cols(); ++j)
    for (Eigen::Index i = 0; i < env_actions.rows(); ++i)
      env_actions(i, j) = std::clamp(env_actions(i, j), space.low()[i], space.high()[i]);
}

void SAC::select_actions(const Eigen::MatrixXf& obs, bool warmup, Eigen::MatrixXf& env_actions,
                         Eigen::MatrixXf& buffer_actions) {
  const Eigen::Index n = obs.cols();
  buffer_actions.resize(action_dim_, n);
  if (warmup) {
    // np.array([action_space.sample() for _ in range(n_envs)]), then scale_action.
    env_actions.resize(action_dim_, n);
    for (Eigen::Index e = 0; e < n; ++e)
      setup_.action_space.sample(action_rng_,
                                 std::span<float>(env_actions.col(e).data(), action_dim_));
    scale_actions(setup_.action_space, env_actions, buffer_actions);
  } else {
    sync_acting_actor();
    acting_log_prob_.resize(n);
    acting_actor_.sample(obs, action_rng_, buffer_actions, acting_log_prob_);
  }
  if (action_noise_.enabled()) {
    // SB3 adds the noise in warmup too: clip(scaled + noise(), -1, 1).
    action_noise_.sample(noise_rng_, exploration_noise_);
    buffer_actions = (buffer_actions + exploration_noise_).cwiseMax(-1.0f).cwiseMin(1.0f);
  }
  to_env_actions(buffer_actions, env_actions);
}

void SAC::predict(const Eigen::Ref<const Eigen::MatrixXf>& obs, bool deterministic,
                  Eigen::MatrixXf& actions) {
  sync_acting_actor();
  scaled_actions_.resize(action_dim_, obs.cols());
  if (deterministic) {
    acting_actor_.mode(obs, scaled_actions_);
  } else {
    acting_log_prob_.resize(obs.cols());
    acting_actor_.sample(obs, predict_rng_, scaled_actions_, acting_log_prob_);
  }
  to_env_actions(scaled_actions_, actions);
}

SacStepStats SAC::train_on_batch(const ReplayBatch& b, float lr, bool update_target) {
  const Eigen::Index batch = b.obs.cols();
  if (obs_action_.cols() != batch) resize_workspaces(batch);
  const auto a_rows = static_cast<Eigen::Index>(action_dim_);
  SacStepStats stats;

  // Policy samples for s' (no gradient) and s (kept for the actor's backward): the actor's
  // Mlp keeps only its last forward, so s goes second. Noise is drawn for s first, as SB3 does.
  fill_normal(train_rng_, policy_noise_);
  fill_normal(train_rng_, next_noise_);
  actor_.sample_from_noise(b.next_obs, next_noise_, next_actions_, next_log_prob_);
  actor_.sample_from_noise(b.obs, policy_noise_, actions_pi_, log_prob_);

  // Entropy coefficient: the value before this step's update is used below (SB3 detaches it).
  const float alpha = ent_coef_.value();
  stats.ent_coef = alpha;
  if (ent_coef_.learned()) stats.ent_coef_loss = ent_coef_.update(log_prob_, lr);

  // Soft Bellman target from the target critics (th.no_grad()).
  next_obs_action_.topRows(obs_dim_) = b.next_obs;
  next_obs_action_.bottomRows(a_rows) = next_actions_;
  for_each_critic([&](size_t i) { critics_[i].compute_target_values(next_obs_action_); });
  sac_critic_target(b.rewards, b.dones, target_values_, next_log_prob_, alpha,
                    static_cast<float>(config_.off_policy.gamma), target_q_);

  // Critic update: critic_loss = 0.5 * sum_i mse(Q_i(s, a), y), one Adam step; then the updated
  // critics evaluate the policy's actions for the actor loss (SB3 order).
  obs_action_.topRows(obs_dim_) = b.obs;
  obs_action_.bottomRows(a_rows) = b.actions;
  obs_action_pi_.topRows(obs_dim_) = b.obs;
  obs_action_pi_.bottomRows(a_rows) = actions_pi_;
  for_each_critic([&](size_t i) {
    critic_losses_[i] = critics_[i].loss_and_gradient(obs_action_, target_q_);
    critics_[i].step(lr);
    critics_[i].compute_values(obs_action_pi_);
  });
  for (double l : critic_losses_) stats.critic_loss += l;

  // Actor loss mean(alpha log pi - min_i Q_i(s, a_pi)): dQ/da through the critics, then
  // pathwise through the squashed Gaussian into the actor; only the actor is stepped.
  stats.actor_loss = sac_actor_loss(q_values_, log_prob_, alpha, grad_q_, grad_log_prob_);
  const auto tau = static_cast<float>(config_.off_policy.tau);
  for_each_critic([&](size_t i) {
    critics_[i].compute_action_gradient(grad_q_[i], action_dim_);
    if (update_target) critics_[i].soft_update(tau);
  });
  grad_actions_ = critics_[0].action_gradient();
  for (size_t i = 1; i < critics_.size(); ++i) grad_actions_ += critics_[i].action_gradient();
  actor_.net().zero_grad();
  actor_.backward(grad_actions_, grad_log_prob_);
  actor_optimizer_.step(lr);
  acting_stale_ = true;
  return stats;
}

void SAC::train(int gradient_steps, Logger* logger) {
  OffPolicyState& state = *state_;
  // SB3 _update_learning_rate: the same scheduled lr for actor, critic and ent_coef optimizers.
  const auto lr = static_cast<float>(config_.learning_rate(state.progress_remaining));
  SacStepStats sum;
  for (int step = 0; step < gradient_steps; ++step) {
    state.buffer.sample(config_.off_policy.batch_size, sample_rng_, batch_);
    // SB3: `if gradient_step % self.target_update_interval == 0`, counted within this call.
    const SacStepStats s = train_on_batch(batch_, lr, step % config_.target_update_interval == 0);
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

void SAC::learn(VecEnv& env, int64_t total_timesteps, TrainingHooks& hooks) {
  if (env.num_envs() != setup_.n_envs)
    throw std::invalid_argument("SAC: env has " + std::to_string(env.num_envs()) +
                                " copies, the algorithm was built for " +
                                std::to_string(setup_.n_envs));
  if (!state_) {
    state_.emplace(
        OffPolicyState{ReplayBuffer(config_.off_policy.buffer_size, setup_.n_envs, obs_dim_,
                                    action_dim_, config_.off_policy.handle_timeout_termination),
                       {},
                       0,
                       1.0});
  }
  OffPolicyCallbacks callbacks;
  callbacks.select_actions = [this](const Eigen::MatrixXf& obs, bool warmup,
                                    Eigen::MatrixXf& env_actions, Eigen::MatrixXf& buffer_actions) {
    select_actions(obs, warmup, env_actions, buffer_actions);
  };
  callbacks.on_episode_end = [this](int e) { action_noise_.reset(e); };
  callbacks.train = [this](int gradient_steps, Logger* logger) { train(gradient_steps, logger); };
  off_policy_learn(env, total_timesteps, hooks, config_.off_policy, *state_, callbacks,
                   num_timesteps_);
}

void SAC::save(TensorMap& tensors) const {
  actor_.save("actor", tensors);
  for (size_t i = 0; i < critics_.size(); ++i) {
    const std::string q = "qf" + std::to_string(i);
    critics_[i].save("critic." + q, "critic_target." + q, tensors);
  }
  ent_coef_.save(tensors);
}

void SAC::load(const TensorMap& tensors) {
  actor_.load("actor", tensors);
  for (size_t i = 0; i < critics_.size(); ++i) {
    const std::string q = "qf" + std::to_string(i);
    critics_[i].load("critic." + q, "critic_target." + q, tensors);
  }
  ent_coef_.load(tensors);
  acting_stale_ = true;
}

}  // namespace rlrun
