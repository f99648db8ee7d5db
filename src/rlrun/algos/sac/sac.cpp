#include "rlrun/algos/sac/sac.hpp"

#include <stdexcept>
#include <string>

#include "rlrun/algos/common/batch_lanes.hpp"
#include "rlrun/algos/common/rng_streams.hpp"
#include "rlrun/algos/common/training_state.hpp"
#include "rlrun/env/vec_env.hpp"

namespace rlrun {

namespace {
// Weights use the seed itself; rng_streams.hpp has the acting, noise and replay streams. Two
// more: the actor's reparameterisation noise in updates, and predict() (so evaluation during
// training never shifts the training streams).
constexpr uint64_t kTrainStream = 0x9e3779b97f4a7c15ULL;
constexpr uint64_t kPredictStream = 0xda942042e4dd58b5ULL;

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

ConfigProblems SAC::check(const Config& config, const AlgorithmSetup& setup) {
  ConfigProblems out;
  check_box_actor_spaces(out, setup);
  check_gradient_steps(out, config.off_policy.gradient_steps);
  check_net_arch(out, "policy.net_arch", config.policy.net_arch);
  const int obs = setup.observation_space.flat_dim(), act = setup.action_space.flat_dim();
  // Actor (mean and log std heads) and, per critic, its target; each replicated per core.
  check_network_memory(out, "policy.net_arch", obs, config.policy.net_arch, 2 * act, 2,
                       config.off_policy.batch_size);
  check_network_memory(out, "policy.net_arch", obs + act, config.policy.net_arch, 1,
                       4 * config.policy.n_critics, config.off_policy.batch_size);
  check_replay_memory(out, config.off_policy.buffer_size, setup);
  return out;
}

SAC::SAC(const Config& config, const AlgorithmSetup& setup)
    : config_(checked(config)),
      setup_(setup),
      obs_dim_(setup.observation_space.flat_dim()),
      action_dim_(BoxActionSelection::checked_action_dim(setup, "SAC")),
      init_rng_(setup.seed),
      sample_rng_(setup.seed ^ kSampleStream),
      train_rng_(setup.seed ^ kTrainStream),
      predict_rng_(setup.seed ^ kPredictStream),
      ent_coef_(config.ent_coef, config.target_entropy, action_dim_),
      acting_(setup, config.action_noise) {
  const Activation act = parse_activation(config_.policy.activation_fn);
  lanes_.reserve(2);
  for (int lane = 0; lane < 2; ++lane)
    lanes_.emplace_back(obs_dim_, action_dim_, config_.policy.net_arch, act,
                        config_.policy.n_critics);
  // SB3 SACPolicy._build: actor first, then the critics; torch's default Linear init for all.
  // Adam with torch's eps 1e-8 everywhere; SB3 steps all critics with one Adam over their
  // concatenated parameters, which is element-wise, so one Adam per critic is the same update.
  SacLane& primary = lanes_.front();
  primary.init(init_rng_);
  actor_optimizer_ = Adam({primary.actor().net().block()});
  for (ContinuousCritic& c : primary.critics())
    critic_optimizers_.emplace_back(std::vector<ParamBlock>{c.q().block()});
  acting_actor_ = primary.actor();
  resize_workspaces(config_.off_policy.batch_size);
}

void SAC::resize_workspaces(Eigen::Index batch) {
  policy_noise_.resize(action_dim_, batch);
  next_noise_.resize(action_dim_, batch);
  target_q_.resize(1, batch);
  log_prob_.resize(batch);
}

void SAC::sync_acting_actor() {
  if (!acting_stale_) return;
  acting_actor_.net().params() = actor().net().params();
  acting_stale_ = false;
}

void SAC::select_actions(const Eigen::MatrixXf& obs, bool warmup, Eigen::MatrixXf& env_actions,
                         Eigen::MatrixXf& buffer_actions) {
  acting_.select(
      obs, warmup,
      [&](Rng& rng, Eigen::MatrixXf& actions) {
        // A stochastic sample of the policy (SB3 predict with deterministic=False).
        sync_acting_actor();
        actions.resize(action_dim_, obs.cols());
        acting_log_prob_.resize(obs.cols());
        acting_actor_.sample(obs, rng, actions, acting_log_prob_);
      },
      env_actions, buffer_actions);
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
  acting_.to_env_actions(scaled_actions_, actions);
}

SacStepStats SAC::train_on_batch(const ReplayBatch& b, float lr, bool update_target) {
  const Eigen::Index n = b.obs.cols();
  if (target_q_.cols() != n) resize_workspaces(n);
  const float inv_batch = 1.0f / static_cast<float>(n);
  const auto gamma = static_cast<float>(config_.off_policy.gamma);
  SacStepStats stats;

  // Reparameterisation noise for the whole batch before the split (so the stream does not
  // depend on it): for s first, then s', as SB3 samples.
  fill_normal(train_rng_, policy_noise_);
  fill_normal(train_rng_, next_noise_);
  // Entropy coefficient: the value before this step's update is used below (SB3 detaches it).
  const float alpha = ent_coef_.value();
  stats.ent_coef = alpha;

  // Critics: policy samples, soft Bellman target y, 0.5 * sum_i mse(Q_i(s, a), y); one step.
  int lanes = run_batch_lanes(n, [&](int lane, Eigen::Index begin, Eigen::Index count) {
    if (lane > 0) lanes_[lane].pull_critic_pass_params(lanes_[0]);
    lane_losses_[lane] = lanes_[lane].critic_pass(b, begin, count, next_noise_, policy_noise_,
                                                  alpha, gamma, inv_batch, log_prob_, target_q_);
  });
  std::vector<ContinuousCritic>& critics = lanes_[0].critics();
  for (int lane = 1; lane < lanes; ++lane)
    for (size_t i = 0; i < critics.size(); ++i)
      critics[i].q().grads() += lanes_[lane].critics()[i].q().grads();
  stats.critic_loss = lanes == 2 ? lane_losses_[0] + lane_losses_[1] : lane_losses_[0];
  // ent_coef_loss = -(log_alpha * (log_prob + target_entropy).detach()).mean(), one step.
  if (ent_coef_.learned()) stats.ent_coef_loss = ent_coef_.update(log_prob_, lr);
  for (Adam& optimizer : critic_optimizers_) optimizer.step(lr);

  // Actor: mean(alpha log pi - min_i Q_i(s, a_pi)) through the updated critics; one step.
  lanes = run_batch_lanes(n, [&](int lane, Eigen::Index begin, Eigen::Index count) {
    if (lane > 0) lanes_[lane].pull_actor_pass_params(lanes_[0]);
    lane_losses_[lane] = lanes_[lane].actor_pass(b, begin, count, alpha, inv_batch);
  });
  for (int lane = 1; lane < lanes; ++lane)
    actor().net().grads() += lanes_[lane].actor().net().grads();
  stats.actor_loss = lanes == 2 ? lane_losses_[0] + lane_losses_[1] : lane_losses_[0];
  actor_optimizer_.step(lr);
  acting_stale_ = true;

  if (update_target) {
    const auto tau = static_cast<float>(config_.off_policy.tau);
    for (ContinuousCritic& c : critics) c.soft_update(tau);
  }
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
  OffPolicyState& state = off_policy_state();
  OffPolicyCallbacks callbacks;
  callbacks.select_actions = [this](const Eigen::MatrixXf& obs, bool warmup,
                                    Eigen::MatrixXf& env_actions, Eigen::MatrixXf& buffer_actions) {
    select_actions(obs, warmup, env_actions, buffer_actions);
  };
  callbacks.on_episode_end = [this](int e) { acting_.on_episode_end(e); };
  callbacks.train = [this](int gradient_steps, Logger* logger) { train(gradient_steps, logger); };
  off_policy_learn(env, total_timesteps, hooks, config_.off_policy, state, callbacks,
                   num_timesteps_);
}

void SAC::save(TensorMap& tensors) const {
  actor().save("actor", tensors);
  for (size_t i = 0; i < critics().size(); ++i) {
    const std::string q = "qf" + std::to_string(i);
    critics()[i].save("critic." + q, "critic_target." + q, tensors);
  }
  ent_coef_.save(tensors);
}

void SAC::load(const TensorMap& tensors) {
  actor().load("actor", tensors);
  for (size_t i = 0; i < critics().size(); ++i) {
    const std::string q = "qf" + std::to_string(i);
    critics()[i].load("critic." + q, "critic_target." + q, tensors);
  }
  ent_coef_.load(tensors);
  acting_stale_ = true;
}

OffPolicyState& SAC::off_policy_state() {
  if (!state_) state_.emplace(config_.off_policy, setup_.n_envs, obs_dim_, action_dim_);
  return *state_;
}

void SAC::save_training_state(StateWriter& out) const {
  out.put_int("num_timesteps", num_timesteps_);
  out.put_int("n_updates", n_updates_);
  out.put_rng("sample_rng", sample_rng_);
  out.put_rng("train_rng", train_rng_);
  out.put_rng("predict_rng", predict_rng_);
  acting_.write_state(out.sub("acting"));
  write_adam(out.sub("actor_optimizer"), actor_optimizer_);
  write_adams(out, "critic_optimizer", critic_optimizers_);
  ent_coef_.write_state(out.sub("ent_coef"));
  write_off_policy_state(out, state_);
}

void SAC::load_training_state(const StateReader& in) {
  num_timesteps_ = in.get_int("num_timesteps");
  n_updates_ = in.get_int("n_updates");
  in.get_rng("sample_rng", sample_rng_);
  in.get_rng("train_rng", train_rng_);
  in.get_rng("predict_rng", predict_rng_);
  acting_.read_state(in.sub("acting"));
  read_adam(in.sub("actor_optimizer"), actor_optimizer_);
  read_adams(in, "critic_optimizer", critic_optimizers_);
  ent_coef_.read_state(in.sub("ent_coef"));
  read_off_policy_state(in, [this]() -> OffPolicyState& { return off_policy_state(); });
  acting_stale_ = true;
}

}  // namespace rlrun
