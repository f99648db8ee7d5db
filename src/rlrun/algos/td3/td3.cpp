#include "rlrun/algos/td3/td3.hpp"

#include <stdexcept>
#include <string>
#include <utility>

#include "rlrun/algos/common/batch_lanes.hpp"
#include "rlrun/algos/common/polyak.hpp"
#include "rlrun/algos/common/rng_streams.hpp"
#include "rlrun/algos/common/training_state.hpp"
#include "rlrun/algos/td3/td3_target.hpp"
#include "rlrun/env/vec_env.hpp"

namespace rlrun {

namespace {
// Weights use the seed itself; rng_streams.hpp has the acting, noise and replay streams.
constexpr uint64_t kSmoothingStream = 0xc2b2ae3d27d4eb4fULL;  // target policy smoothing noise

// Logger keys built once (the logger takes std::string; these outgrow the small-string buffer).
const std::string kKeyNUpdates = "train/n_updates";
const std::string kKeyActorLoss = "train/actor_loss";
const std::string kKeyCriticLoss = "train/critic_loss";
const std::string kKeyLearningRate = "train/learning_rate";

const TD3::Config& checked(const TD3::Config& c, const std::string& id) {
  const OffPolicyConfig& o = c.off_policy;
  if (o.batch_size < 1) throw std::invalid_argument(id + ": batch_size must be >= 1");
  if (o.buffer_size < 1) throw std::invalid_argument(id + ": buffer_size must be >= 1");
  if (!(o.tau >= 0.0 && o.tau <= 1.0)) throw std::invalid_argument(id + ": tau must be in [0, 1]");
  if (c.policy_delay < 1) throw std::invalid_argument(id + ": policy_delay must be >= 1");
  if (!(c.target_policy_noise >= 0.0) || !(c.target_noise_clip >= 0.0))
    throw std::invalid_argument(id + ": target_policy_noise and target_noise_clip must be >= 0");
  if (c.policy.n_critics < 1) throw std::invalid_argument(id + ": policy.n_critics must be >= 1");
  return c;
}

}  // namespace

ConfigProblems TD3::check(const Config& config, const AlgorithmSetup& setup) {
  ConfigProblems out;
  check_box_actor_spaces(out, setup);
  check_gradient_steps(out, config.off_policy.gradient_steps);
  check_net_arch(out, "policy.net_arch", config.policy.net_arch);
  const int obs = setup.observation_space.flat_dim(), act = setup.action_space.flat_dim();
  // Actor and its target, critics and their targets, each replicated per core.
  check_network_memory(out, "policy.net_arch", obs, config.policy.net_arch, act, 4,
                       config.off_policy.batch_size);
  check_network_memory(out, "policy.net_arch", obs + act, config.policy.net_arch, 1,
                       4 * config.policy.n_critics, config.off_policy.batch_size);
  check_replay_memory(out, config.off_policy.buffer_size, setup);
  return out;
}

TD3::TD3(const Config& config, const AlgorithmSetup& setup, std::string id)
    : id_(std::move(id)),
      config_(checked(config, id_)),
      setup_(setup),
      obs_dim_(setup.observation_space.flat_dim()),
      action_dim_(BoxActionSelection::checked_action_dim(setup, id_)),
      init_rng_(setup.seed),
      sample_rng_(setup.seed ^ kSampleStream),
      smoothing_rng_(setup.seed ^ kSmoothingStream),
      acting_actor_(obs_dim_, action_dim_, config.policy.net_arch,
                    parse_activation(config.policy.activation_fn)),
      acting_(setup, config.action_noise) {
  const Activation act = parse_activation(config_.policy.activation_fn);
  lanes_.reserve(2);
  for (int lane = 0; lane < 2; ++lane)
    lanes_.emplace_back(obs_dim_, action_dim_, config_.policy.net_arch, act,
                        config_.policy.n_critics);
  // SB3 TD3Policy._build: actor (target a copy), then the critics (targets copies); torch's
  // default Linear init; Adam with torch's defaults (eps 1e-8) for the actor and the critics.
  // SB3 steps all critics with one Adam over their concatenated parameters: Adam is
  // element-wise with one step count, so one Adam per critic is the same update.
  Td3Lane& primary = lanes_.front();
  primary.init(init_rng_);
  acting_actor_.net().params() = primary.actor().net().params();
  actor_optimizer_ = Adam({primary.actor().net().block()});
  for (ContinuousCritic& c : primary.critics())
    critic_optimizers_.emplace_back(std::vector<ParamBlock>{c.q().block()});
  smoothing_noise_.resize(action_dim_, config_.off_policy.batch_size);
  target_q_.resize(1, config_.off_policy.batch_size);
}

void TD3::sync_acting_actor() {
  if (!acting_stale_) return;
  acting_actor_.net().params() = actor().net().params();
  acting_stale_ = false;
}

void TD3::select_actions(const Eigen::MatrixXf& obs, bool warmup, Eigen::MatrixXf& env_actions,
                         Eigen::MatrixXf& buffer_actions) {
  // SB3 predicts (actor, unscaled to the bounds) and scales back to [-1, 1]; the actor's tanh
  // output is that scaled action already.
  acting_.select(
      obs, warmup,
      [&](Rng&, Eigen::MatrixXf& actions) {
        sync_acting_actor();
        actions = acting_actor_.forward(obs);
      },
      env_actions, buffer_actions);
}

void TD3::predict(const Eigen::Ref<const Eigen::MatrixXf>& obs, bool /*deterministic*/,
                  Eigen::MatrixXf& actions) {
  sync_acting_actor();
  acting_.to_env_actions(acting_actor_.forward(obs), actions);
}

double TD3::critic_loss_and_gradients(const ReplayBatch& batch) {
  const Eigen::Index n = batch.obs.cols();
  if (smoothing_noise_.cols() != n) {
    smoothing_noise_.resize(action_dim_, n);
    target_q_.resize(1, n);
  }
  // Drawn for the whole batch before the split, so the stream does not depend on it.
  sample_target_smoothing_noise(smoothing_rng_, static_cast<float>(config_.target_policy_noise),
                                static_cast<float>(config_.target_noise_clip), smoothing_noise_);
  const auto gamma = static_cast<float>(config_.off_policy.gamma);
  const float inv_batch = 1.0f / static_cast<float>(n);
  const int lanes = run_batch_lanes(n, [&](int lane, Eigen::Index begin, Eigen::Index count) {
    if (lane > 0) lanes_[lane].pull_critic_pass_params(lanes_[0]);
    lane_losses_[lane] = lanes_[lane].critic_pass(batch, begin, count, smoothing_noise_, gamma,
                                                  inv_batch, target_q_);
  });
  std::vector<ContinuousCritic>& critics = lanes_[0].critics();
  for (int lane = 1; lane < lanes; ++lane)
    for (size_t i = 0; i < critics.size(); ++i)
      critics[i].q().grads() += lanes_[lane].critics()[i].q().grads();
  return lanes == 2 ? lane_losses_[0] + lane_losses_[1] : lane_losses_[0];
}

double TD3::actor_loss_and_gradient(const ReplayBatch& batch) {
  const Eigen::Index n = batch.obs.cols();
  const float inv_batch = 1.0f / static_cast<float>(n);
  const int lanes = run_batch_lanes(n, [&](int lane, Eigen::Index begin, Eigen::Index count) {
    if (lane > 0) lanes_[lane].pull_actor_pass_params(lanes_[0]);
    lane_losses_[lane] = lanes_[lane].actor_pass(batch, begin, count, inv_batch);
  });
  for (int lane = 1; lane < lanes; ++lane)
    lanes_[0].actor().net().grads() += lanes_[lane].actor().net().grads();
  return lanes == 2 ? lane_losses_[0] + lane_losses_[1] : lane_losses_[0];
}

Td3StepStats TD3::train_on_batch(const ReplayBatch& batch, float lr) {
  ++n_updates_;
  Td3StepStats stats;
  // Critics: y from the target networks, sum of the critics' mse, one optimizer step.
  stats.critic_loss = critic_loss_and_gradients(batch);
  for (Adam& optimizer : critic_optimizers_) optimizer.step(lr);

  // Delayed policy update: the actor through critic 1, then every target by Polyak averaging.
  if (n_updates_ % config_.policy_delay == 0) {
    stats.actor_loss = actor_loss_and_gradient(batch);
    stats.actor_updated = true;
    actor_optimizer_.step(lr);
    acting_stale_ = true;
    const auto tau = static_cast<float>(config_.off_policy.tau);
    for (ContinuousCritic& c : critics()) c.soft_update(tau);
    polyak_update(actor().net().params(), actor_target().net().params(), tau);
  }
  return stats;
}

void TD3::train(int gradient_steps, Logger* logger) {
  OffPolicyState& state = *state_;
  // SB3 _update_learning_rate: one scheduled lr for the actor and critic optimizers.
  const auto lr = static_cast<float>(config_.learning_rate(state.progress_remaining));
  double critic_loss_sum = 0.0, actor_loss_sum = 0.0;
  int actor_updates = 0;
  for (int step = 0; step < gradient_steps; ++step) {
    state.buffer.sample(config_.off_policy.batch_size, sample_rng_, batch_);
    const Td3StepStats s = train_on_batch(batch_, lr);
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

void TD3::learn(VecEnv& env, int64_t total_timesteps, TrainingHooks& hooks) {
  if (env.num_envs() != setup_.n_envs)
    throw std::invalid_argument(id_ + ": env has " + std::to_string(env.num_envs()) +
                                " copies, the algorithm was built for " +
                                std::to_string(setup_.n_envs));
  OffPolicyState& state = off_policy_state();
  OffPolicyCallbacks callbacks;
  callbacks.select_actions = [this](const Eigen::MatrixXf& obs, bool warmup,
                                    Eigen::MatrixXf& env_actions, Eigen::MatrixXf& buffer_actions) {
    select_actions(obs, warmup, env_actions, buffer_actions);
  };
  // SB3 collect_rollouts: action_noise.reset(indices=[idx]) for each finished episode.
  callbacks.on_episode_end = [this](int e) { acting_.on_episode_end(e); };
  callbacks.train = [this](int gradient_steps, Logger* logger) { train(gradient_steps, logger); };
  off_policy_learn(env, total_timesteps, hooks, config_.off_policy, state, callbacks,
                   num_timesteps_);
}

void TD3::save(TensorMap& tensors) const {
  // SB3 TD3Policy.state_dict(): actor.mu.*, actor_target.mu.*, critic.qf<i>.*,
  // critic_target.qf<i>.*
  actor().save("actor", tensors);
  actor_target().save("actor_target", tensors);
  for (size_t i = 0; i < critics().size(); ++i) {
    const std::string q = "qf" + std::to_string(i);
    critics()[i].save("critic." + q, "critic_target." + q, tensors);
  }
}

void TD3::load(const TensorMap& tensors) {
  actor().load("actor", tensors);
  actor_target().load("actor_target", tensors);
  for (size_t i = 0; i < critics().size(); ++i) {
    const std::string q = "qf" + std::to_string(i);
    critics()[i].load("critic." + q, "critic_target." + q, tensors);
  }
  acting_stale_ = true;
}

OffPolicyState& TD3::off_policy_state() {
  if (!state_) state_.emplace(config_.off_policy, setup_.n_envs, obs_dim_, action_dim_);
  return *state_;
}

void TD3::save_training_state(StateWriter& out) const {
  out.put_int("num_timesteps", num_timesteps_);
  out.put_int("n_updates", n_updates_);
  out.put_rng("sample_rng", sample_rng_);
  out.put_rng("smoothing_rng", smoothing_rng_);
  acting_.write_state(out.sub("acting"));
  write_adam(out.sub("actor_optimizer"), actor_optimizer_);
  write_adams(out, "critic_optimizer", critic_optimizers_);
  write_off_policy_state(out, state_);
}

void TD3::load_training_state(const StateReader& in) {
  num_timesteps_ = in.get_int("num_timesteps");
  n_updates_ = in.get_int("n_updates");
  in.get_rng("sample_rng", sample_rng_);
  in.get_rng("smoothing_rng", smoothing_rng_);
  acting_.read_state(in.sub("acting"));
  read_adam(in.sub("actor_optimizer"), actor_optimizer_);
  read_adams(in, "critic_optimizer", critic_optimizers_);
  read_off_policy_state(in, [this]() -> OffPolicyState& { return off_policy_state(); });
  acting_stale_ = true;
}

}  // namespace rlrun
