#include "rlrun/algos/common/off_policy.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <stdexcept>
#include <utility>

#include "rlrun/algos/common/session_time.hpp"
#include "rlrun/core/config_validation.hpp"
#include "rlrun/core/resource_limits.hpp"
#include "rlrun/env/goal_env.hpp"
#include "rlrun/env/vec_env.hpp"

namespace rlrun {

void decode(const ConfigNode& node, TrainFreq& out) {
  if (node.is_scalar()) {
    decode(node, out.frequency);
    out.episodes = false;
  } else if (node.is_sequence() && node.size() == 2) {
    decode(node.at(0), out.frequency);
    const std::string unit = node.at(1).as_string();
    if (unit != "step" && unit != "episode")
      node.at(1).fail("train_freq unit must be 'step' or 'episode', got '" + unit + "'");
    out.episodes = unit == "episode";
  } else {
    node.fail("expected an integer (steps) or [N, step|episode]");
  }
  if (out.frequency < 1) node.fail("train_freq must be >= 1");
}

YAML::Node encode(const TrainFreq& value) {
  YAML::Node node(YAML::NodeType::Sequence);
  node.push_back(value.frequency);
  node.push_back(value.episodes ? "episode" : "step");
  node.SetStyle(YAML::EmitterStyle::Flow);
  return node;
}

OffPolicyState::OffPolicyState(const OffPolicyConfig& config, int n_envs,
                               const Space& observation_space, int act_dim) {
  if (config.her()) {
    const ReplayBufferKwargs& kw = config.replay_buffer_kwargs;
    auto her_buffer = std::make_unique<HerReplayBuffer>(
        config.buffer_size, n_envs, observation_space, act_dim, nullptr, kw.n_sampled_goal,
        parse_goal_selection(kw.goal_selection_strategy), config.handle_timeout_termination);
    her = her_buffer.get();
    buffer = std::move(her_buffer);
  } else {
    buffer = std::make_unique<ReplayBuffer>(config.buffer_size, n_envs, observation_space, act_dim,
                                            config.handle_timeout_termination,
                                            config.optimize_memory_usage);
  }
}

void OffPolicyState::write_state(StateWriter out) const {
  buffer->write_state(out.sub("replay_buffer"));
  episode_stats.write_state(out.sub("episode_stats"));
  out.put_int("episode_num", episode_num);
  out.put_double("progress_remaining", progress_remaining);
  put_matrix(out, "last_original_obs", last_original_obs);
}

void OffPolicyState::read_state(const StateReader& in) {
  buffer->read_state(in.sub("replay_buffer"));
  episode_stats.read_state(in.sub("episode_stats"));
  episode_num = in.get_count("episode_num");
  progress_remaining = in.get_double("progress_remaining");
  if (!(progress_remaining >= 0.0 && progress_remaining <= 1.0))  // NaN too: schedules read it
    throw StateMismatch("checkpoint state '" + in.prefix() + "progress_remaining' is " +
                        std::to_string(progress_remaining) + ", outside [0, 1]");
  last_original_obs.resize(0, 0);
  if (in.has("last_original_obs")) {
    last_original_obs.resize(buffer->obs_dim(), buffer->n_envs());
    get_matrix(in, "last_original_obs", last_original_obs);
  }
  restored = true;
}

void check_replay_buffer(ConfigProblems& out, const OffPolicyConfig& config,
                         const AlgorithmSetup& setup) {
  check_replay_memory(out, config.buffer_size, config.optimize_memory_usage, setup);
  if (config.optimize_memory_usage) {
    // SB3 ReplayBuffer.__init__ refuses the pair; HerReplayBuffer has no such option.
    if (config.handle_timeout_termination)
      out.push_back({"optimize_memory_usage",
                     "cannot be used with handle_timeout_termination: true (the buffer keeps no "
                     "final observation for a time-limit truncation to bootstrap from, as SB3); "
                     "set handle_timeout_termination: false"});
    if (config.her())
      out.push_back({"optimize_memory_usage", "HerReplayBuffer does not support it (as SB3)"});
    if (config.buffer_size / setup.n_envs < 2)
      out.push_back(
          {"optimize_memory_usage", "needs buffer_size of at least two transitions per env"});
  }
  if (!config.her()) return;
  const Space& obs = setup.observation_space;
  const auto has = [&](const char* key) {
    return obs.is_dict() &&
           std::find(obs.keys().begin(), obs.keys().end(), key) != obs.keys().end();
  };
  if (!has("observation") || !has("achieved_goal") || !has("desired_goal")) {
    out.push_back({"replay_buffer_class",
                   "HerReplayBuffer needs a goal-conditioned env (a Dict observation with "
                   "observation, achieved_goal and desired_goal, and compute_reward); this one "
                   "observes " +
                       obs.describe()});
    return;
  }
  // The HER bookkeeping: two int64 per transition.
  const std::string problem = memory_problem(
      static_cast<double>(config.buffer_size) * 2.0 * sizeof(int64_t), "HER's episode indices");
  if (!problem.empty()) out.push_back({"buffer_size", problem});
}

void check_box_actor_critic(ConfigProblems& out, const AlgorithmSetup& setup,
                            const OffPolicyConfig& config, const BoxActorCriticShape& shape) {
  check_box_actor_spaces(out, setup);
  check_gradient_steps(out, config.gradient_steps);
  check_net_arch(out, "policy.net_arch", shape.net_arch.pi, shape.net_arch.qf);
  // The actor's CNN and its copies (target, acting copy), the critic's (unless shared) and its
  // target's.
  const FeaturesExtractorSettings& e = shape.extractor;
  const int obs = features_extractor_output_dim(
      out, "policy.features_extractor_class", e, setup.observation_space,
      shape.actor_copies + (shape.share_features_extractor ? 1 : 2), config.batch_size);
  const int act = setup.action_space.flat_dim();
  check_network_memory(out, "policy.net_arch", obs, shape.net_arch.pi, shape.actor_outputs,
                       shape.actor_copies, config.batch_size);
  // Each critic, its target and the second core's activations of both.
  check_network_memory(out, "policy.net_arch", obs + act, shape.net_arch.qf, shape.critic_outputs,
                       4 * shape.n_critics, config.batch_size);
  check_replay_buffer(out, config, setup);
}

OffPolicyAlgorithm::OffPolicyAlgorithm(std::string id, const OffPolicyConfig& config,
                                       const AlgorithmSetup& setup, int buffer_action_dim,
                                       const ReplayStream& replay, bool normalize_images)
    : setup_(setup),
      id_(std::move(id)),
      config_(config),
      buffer_action_dim_(buffer_action_dim),
      replay_rng_(setup.seed ^ replay.stream),
      batch_obs_(setup.observation_space, normalize_images),
      batch_next_obs_(setup.observation_space, normalize_images),
      acting_obs_(setup.observation_space, normalize_images) {
  valid_config(config, id_);
  if (setup.n_envs < 1) throw std::invalid_argument(id_ + ": n_envs must be >= 1");
  checkpoint("num_timesteps", num_timesteps_);
  checkpoint("n_updates", n_updates_);
  checkpoint(replay.key, replay_rng_);
  // The replay buffer and what goes with it, once there is one (a model only evaluated has
  // none); DQN's checkpoints from before the flag always held it.
  checkpoint(
      [this](StateWriter& out) {
        out.put_bool("has_off_policy", state_.has_value());
        if (state_) state_->write_state(out.sub("off_policy"));
      },
      [this](const StateReader& in) {
        if (!in.has("has_off_policy") || in.get_bool("has_off_policy"))
          state().read_state(in.sub("off_policy"));
      });
}

OffPolicyState& OffPolicyAlgorithm::state() {
  if (!state_) state_.emplace(config_, setup_.n_envs, setup_.observation_space, buffer_action_dim_);
  return *state_;
}

const ReplayBatch& OffPolicyAlgorithm::sample_batch() {
  state_->buffer->sample(config_.batch_size, replay_rng_, batch_);
  // SB3 ReplayBuffer._normalize_obs / _normalize_reward: stored originals are normalised with
  // VecNormalize's statistics of now (HER's relabelled goals and rewards included).
  if (step_hook_) {
    step_hook_->normalize_obs(batch_.obs);
    step_hook_->normalize_obs(batch_.next_obs);
    step_hook_->normalize_rewards(batch_.rewards);
  }
  return batch_;
}

struct OffPolicyAlgorithm::LearnCall {
  VecEnv& env;
  TrainingHooks& hooks;
  int64_t total_timesteps;
  int log_interval;  // finished episodes between log dumps
  std::chrono::steady_clock::time_point start;
  int64_t start_timesteps;
  Eigen::MatrixXf last_obs, env_actions, buffer_actions;
  int64_t collected_steps = 0;  // VecEnv steps of the current collect_rollouts
};

void OffPolicyAlgorithm::learn(VecEnv& env, int64_t total_timesteps, TrainingHooks& hooks) {
  if (env.num_envs() != setup_.n_envs)
    throw std::invalid_argument(id_ + ": env has " + std::to_string(env.num_envs()) +
                                " copies, the algorithm was built for " +
                                std::to_string(setup_.n_envs));
  OffPolicyState& s = state();
  if (HerReplayBuffer* her = s.her) {
    // SB3 HerReplayBuffer.set_env: rewards of relabelled goals come from the first env's
    // compute_reward (a restored buffer gets the env here too).
    const GoalEnv* goals = goal_env_of(env.env(0));
    if (!goals)
      throw std::invalid_argument(
          id_ +
          ": replay_buffer_class HerReplayBuffer needs a goal-conditioned env with "
          "compute_reward; " +
          env.env(0).id() +
          " has none (rlrun's goal envs: "
          "BitFlippingEnv-v0, GripperReach-v0, GripperPush-v0, GripperPickAndPlace-v0)");
    her->set_goal_env(goals);
  }
  // Batches are normalised as the env's VecNormalize says while this learn() runs.
  step_hook_ = env.step_hook();
  struct Forget {
    const VecStepHook*& hook;
    ~Forget() { hook = nullptr; }
  } forget{step_hook_};

  LearnCall call{env,
                 hooks,
                 total_timesteps,
                 hooks.log_interval > 0 ? hooks.log_interval : 4,
                 std::chrono::steady_clock::now(),
                 num_timesteps_,
                 {},
                 {},
                 {}};
  // A restored state continues the envs where the checkpoint left them; the last
  // observations are the VecEnv's (the loop below keeps last_obs == env.obs() at safe points).
  const bool continuing = !s.restored && s.continued_env == &env;
  s.continued_env = &env;
  call.last_obs = s.restored || continuing ? env.obs() : env.reset();
  // SB3 _last_original_obs: what the replay buffer stores, VecNormalize's original observations
  // (the same as last_obs without env.normalize). A checkpoint carries it; one written before
  // rlrun kept it holds the VecEnv's.
  if (!s.restored || s.last_original_obs.cols() != setup_.n_envs)
    s.last_original_obs = s.restored ? env.obs() : env.original_obs();
  s.restored = false;

  while (num_timesteps_ < total_timesteps) {
    if (!collect_rollouts(call)) break;
    if (hooks.on_rollout_end) hooks.on_rollout_end(num_timesteps_);
    if (num_timesteps_ > 0 && num_timesteps_ > config_.learning_starts) {
      const int64_t steps = config_.gradient_steps >= 0 ? config_.gradient_steps
                                                        : call.collected_steps * setup_.n_envs;
      if (steps > 0) train(static_cast<int>(steps), hooks.logger);
    }
    // Between rounds nothing is in flight: the state can be saved and resumed exactly.
    if (hooks.at_safe_point && !hooks.at_safe_point(num_timesteps_)) break;
  }
}

bool OffPolicyAlgorithm::collect_rollouts(LearnCall& call) {
  OffPolicyState& s = *state_;
  VecEnv& env = call.env;
  int64_t collected_episodes = 0;
  call.collected_steps = 0;
  while (config_.train_freq.episodes ? collected_episodes < config_.train_freq.frequency
                                     : call.collected_steps < config_.train_freq.frequency) {
    before_collect_step(call.collected_steps);
    const bool warmup = num_timesteps_ < config_.learning_starts;
    select_actions(call.last_obs, warmup, call.env_actions, call.buffer_actions);
    env.step(call.env_actions);
    num_timesteps_ += setup_.n_envs;
    ++call.collected_steps;
    if (call.hooks.on_step && !call.hooks.on_step(num_timesteps_)) return false;
    s.episode_stats.update(env);
    s.buffer->add(s.last_original_obs, call.buffer_actions, env);
    call.last_obs = env.obs();
    s.last_original_obs = env.original_obs();
    s.progress_remaining =
        1.0 - static_cast<double>(num_timesteps_) / static_cast<double>(call.total_timesteps);
    on_step(call.hooks.logger);
    for (int e = 0; e < setup_.n_envs; ++e) {
      if (!env.done(e)) continue;
      ++collected_episodes;
      ++s.episode_num;
      on_episode_end(e);
      if (s.episode_num % call.log_interval == 0) dump_logs(call);
    }
  }
  return true;
}

void OffPolicyAlgorithm::dump_logs(LearnCall& call) {
  if (!call.hooks.logger) return;
  Logger& log = *call.hooks.logger;
  const double elapsed =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - call.start).count();
  log.record("time/episodes", static_cast<double>(state_->episode_num));
  state_->episode_stats.record(log);
  record_session_time(log, elapsed, num_timesteps_ - call.start_timesteps);
  log.record("time/total_timesteps", static_cast<double>(num_timesteps_));
  record_rollout_logs(log);
  log.dump(num_timesteps_);
  if (call.hooks.on_log) call.hooks.on_log(num_timesteps_);
}

}  // namespace rlrun
