#include "rlrun/algos/common/on_policy.hpp"

#include "rlrun/algos/common/session_time.hpp"
#include "rlrun/nn/policy_graph.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <stdexcept>
#include <utility>

#include "rlrun/algos/common/rng_streams.hpp"
#include "rlrun/core/state_dict.hpp"
#include "rlrun/env/vec_env.hpp"

namespace rlrun {

RolloutBuffer::RolloutBuffer(int n_steps, int n_envs, const Space& observation_space, int act_dim,
                             int mask_size)
    : obs(observation_space, int64_t{n_steps} * n_envs),
      actions(act_dim, n_steps * n_envs),
      action_masks(mask_size, mask_size > 0 ? n_steps * n_envs : 0) {
  for (StepEnvMatrix* m : {&rewards, &values, &episode_starts, &log_probs, &advantages, &returns})
    m->resize(n_steps, n_envs);
}

void clip_to_box(const Space& space, Eigen::MatrixXf& actions) {
  if (!space.is_box()) return;
  for (Eigen::Index j = 0; j < actions.cols(); ++j)
    for (Eigen::Index i = 0; i < actions.rows(); ++i)
      actions(i, j) = std::clamp(actions(i, j), space.low()[i], space.high()[i]);
}

std::string export_clip_to_box(PolicyGraph& graph, const Space& space, const std::string& actions) {
  if (!space.is_box()) return actions;
  const Eigen::Map<const Eigen::VectorXf> low(space.low().data(), space.flat_dim());
  const Eigen::Map<const Eigen::VectorXf> high(space.high().data(), space.flat_dim());
  return graph.clamp(actions, low, high);
}

OnPolicyCollector::OnPolicyCollector(const AlgorithmSetup& setup, int n_steps, int act_dim,
                                     int sde_sample_freq, int mask_size)
    : action_space_(setup.action_space),
      buffer_(n_steps, setup.n_envs, setup.observation_space, act_dim, mask_size),
      last_obs_(setup.observation_space.flat_dim(), setup.n_envs),
      env_actions_(setup.action_space.flat_dim(), setup.n_envs),
      final_obs_(setup.observation_space.flat_dim(), 1),
      last_episode_starts_(Eigen::RowVectorXf::Ones(setup.n_envs)) {
  sde_sample_freq_ = sde_sample_freq;
  mask_size_ = mask_size;
  last_masks_ = Eigen::MatrixXf::Ones(mask_size, mask_size > 0 ? setup.n_envs : 0);
  if (n_steps < 1) throw std::invalid_argument("n_steps must be >= 1");
}

void OnPolicyCollector::start(VecEnv& env) {
  if (env.num_envs() != last_obs_.cols())
    throw std::invalid_argument("the env has " + std::to_string(env.num_envs()) +
                                " copies, the algorithm was built for " +
                                std::to_string(last_obs_.cols()));
  if (restored_) {
    restored_ = false;
    continued_env_ = &env;
    return;
  }
  if (continued_env_ == &env) {
    // The envs' present observations: a learn() a callback stopped left last_obs_ a step
    // behind them (as SB3's collect_rollouts returns before it updates _last_obs).
    last_obs_ = env.obs();
    for (int i = 0; i < env.num_envs(); ++i) last_episode_starts_(i) = env.done(i) ? 1.0f : 0.0f;
    if (mask_size_ > 0) read_action_masks(env, mask_readers_, last_masks_, -1);
    return;
  }
  continued_env_ = &env;
  last_obs_ = env.reset();
  if (mask_size_ > 0) read_action_masks(env, mask_readers_, last_masks_, -1);
  last_episode_starts_.setOnes();
  iterations_ = 0;
}

void OnPolicyCollector::write_state(StateWriter out) const {
  put_matrix(out, "last_obs", last_obs_);
  put_matrix(out, "last_episode_starts", last_episode_starts_);
  out.put_int("iterations", iterations_);
  episode_stats_.write_state(out.sub("episode_stats"));
  if (mask_size_ > 0) put_matrix(out, "last_masks", last_masks_);
}

void OnPolicyCollector::read_state(const StateReader& in) {
  get_matrix(in, "last_obs", last_obs_);
  get_matrix(in, "last_episode_starts", last_episode_starts_);
  iterations_ = in.get_count("iterations");
  episode_stats_.read_state(in.sub("episode_stats"));
  if (mask_size_ > 0) {
    get_matrix(in, "last_masks", last_masks_);  // the shape the configuration fixes
    for (Eigen::Index e = 0; e < last_masks_.cols(); ++e) {
      const std::string problem = action_mask_problem(
          action_space_, {last_masks_.col(e).data(), static_cast<size_t>(mask_size_)});
      if (!problem.empty())
        throw StateMismatch("checkpoint state '" + in.prefix() + "last_masks' (env " +
                            std::to_string(e) + "): " + problem);
    }
  }
  restored_ = true;
}

bool OnPolicyCollector::collect(VecEnv& env, RolloutPolicy& policy, Rng& rng, float gamma,
                                float gae_lambda, TrainingHooks& hooks, int64_t& num_timesteps) {
  const int n_envs = env.num_envs();
  const int n_steps = static_cast<int>(buffer_.rewards.rows());
  // SB3 collect_rollouts: "Sample new weights for the state dependent exploration".
  if (policy.use_sde()) policy.reset_noise(rng, n_envs);
  for (int step = 0; step < n_steps; ++step) {
    if (policy.use_sde() && sde_sample_freq_ > 0 && step % sde_sample_freq_ == 0)
      policy.reset_noise(rng, n_envs);
    policy.act(step, last_obs_, last_episode_starts_, rng, step_actions_, step_values_,
               step_log_probs_, mask_size_ > 0 ? &last_masks_ : nullptr);
    env_actions_ = step_actions_;
    clip_to_box(action_space_, env_actions_);
    env.step(env_actions_);
    num_timesteps += n_envs;
    if (hooks.on_step && !hooks.on_step(num_timesteps)) return false;
    episode_stats_.update(env);

    for (int e = 0; e < n_envs; ++e) {
      float reward = static_cast<float>(env.rewards()(e));
      // Timeout bootstrap (SB3 on_policy_algorithm.py): a truncated, non-terminal step gets
      // gamma * V(final_obs) added to its reward, since GAE then treats it as an episode end.
      if (env.truncated(e) && !env.terminated(e)) {
        final_obs_ = env.final_obs().col(e);
        reward += gamma * policy.terminal_value(final_obs_, e);
      }
      const int k = step * n_envs + e;
      buffer_.obs.set(k, last_obs_.col(e).data());
      buffer_.actions.col(k) = step_actions_.col(e);
      buffer_.rewards(step, e) = reward;
      buffer_.episode_starts(step, e) = last_episode_starts_(e);
      buffer_.values(step, e) = step_values_(e);
      buffer_.log_probs(step, e) = step_log_probs_(e);
      if (mask_size_ > 0) buffer_.action_masks.col(k) = last_masks_.col(e);
      last_episode_starts_(e) = env.done(e) ? 1.0f : 0.0f;
    }
    last_obs_ = env.obs();
    // sb3-contrib get_action_masks(env) at the next step: the masks of the new observations.
    if (mask_size_ > 0) read_action_masks(env, mask_readers_, last_masks_, num_timesteps);
  }
  policy.last_values(last_obs_, last_episode_starts_, terminal_value_);
  compute_gae(buffer_.rewards, buffer_.values, buffer_.episode_starts, terminal_value_,
              last_episode_starts_, gamma, gae_lambda, buffer_.advantages, buffer_.returns);
  return true;
}

OnPolicyAlgorithm::OnPolicyAlgorithm(std::string id, const AlgorithmSetup& setup,
                                     const ActorCriticPolicyConfig& policy, const Rollout& rollout,
                                     bool maskable, bool env_masks)
    : setup_(setup),
      // The weights (and gSDE's first exploration matrix) from the seed itself.
      policy_([&] {
        Rng init_rng(setup.seed);
        return ActorCriticPolicy(setup.observation_space, setup.action_space, policy, init_rng,
                                 rollout.use_sde, maskable);
      }()),
      collector_(setup, rollout.n_steps, policy_.action_dim(), rollout.sde_sample_freq,
                 maskable && env_masks ? policy_.mask_size() : 0),
      action_rng_(setup.seed ^ kActionStream),
      id_(std::move(id)),
      env_masks_(maskable && env_masks),
      gamma_(static_cast<float>(rollout.gamma)),
      gae_lambda_(static_cast<float>(rollout.gae_lambda)) {
  register_state();
}

OnPolicyAlgorithm::OnPolicyAlgorithm(std::string id, const AlgorithmSetup& setup,
                                     const Space& policy_input,
                                     const ActorCriticPolicyConfig& policy, const Rollout& rollout)
    : setup_(setup),
      policy_([&] {
        Rng init_rng(setup.seed);
        return ActorCriticPolicy(policy_input, setup.action_space, policy, init_rng,
                                 rollout.use_sde, false);
      }()),
      collector_(setup, rollout.n_steps, policy_.action_dim(), rollout.sde_sample_freq, 0),
      action_rng_(setup.seed ^ kActionStream),
      id_(std::move(id)),
      gamma_(static_cast<float>(rollout.gamma)),
      gae_lambda_(static_cast<float>(rollout.gae_lambda)) {
  register_state();
}

void OnPolicyAlgorithm::register_state() {
  policy_.set_thread_pool(setup_.pool);
  checkpoint("num_timesteps", num_timesteps_);
  checkpoint("n_updates", n_updates_);
  checkpoint("action_rng", action_rng_);
  checkpoint("collector", collector_);
  if (policy_.use_sde()) checkpoint("sde", policy_.sde());
}

void OnPolicyAlgorithm::predict(const Eigen::Ref<const Eigen::MatrixXf>& obs, bool deterministic,
                                Eigen::MatrixXf& actions) {
  policy_.act(obs, action_rng_, deterministic, actions, predict_values_, predict_log_probs_);
  clip_to_box(setup_.action_space, actions);
}

void OnPolicyAlgorithm::predict_masked(const Eigen::Ref<const Eigen::MatrixXf>& obs,
                                       const Eigen::Ref<const Eigen::MatrixXf>& masks,
                                       bool deterministic, Eigen::MatrixXf& actions) {
  const int size = policy_.mask_size();
  if (size == 0) throw std::logic_error(id_ + " takes no action masks");
  if (masks.rows() != size || masks.cols() != obs.cols())
    throw std::invalid_argument(id_ + ": action masks are " + std::to_string(masks.rows()) + " x " +
                                std::to_string(masks.cols()) + ", expected " +
                                std::to_string(size) + " x " + std::to_string(obs.cols()) +
                                " (one mask of " + std::to_string(size) + " entries per " +
                                "observation for " + setup_.action_space.describe() + ")");
  predict_masks_ = masks;
  for (Eigen::Index j = 0; j < predict_masks_.cols(); ++j) {
    const std::string problem = action_mask_problem(
        setup_.action_space, {predict_masks_.col(j).data(), static_cast<size_t>(size)});
    if (!problem.empty())
      throw std::invalid_argument(id_ + ": observation " + std::to_string(j) + ": " + problem);
  }
  policy_.act(obs, action_rng_, deterministic, actions, predict_values_, predict_log_probs_,
              &predict_masks_);
}

void OnPolicyAlgorithm::export_policy(PolicyGraph& graph, const std::string& obs,
                                      bool with_value) const {
  policy_.export_to(graph, obs, setup_.action_space, with_value);
  graph.set_action(export_clip_to_box(graph, setup_.action_space, graph.action()));
}

void OnPolicyAlgorithm::learn(VecEnv& env, int64_t total_timesteps, TrainingHooks& hooks) {
  const auto start = std::chrono::steady_clock::now();
  const int64_t start_timesteps = num_timesteps_;
  collector_.start(env);
  const int log_interval = hooks.log_interval > 0 ? hooks.log_interval : 1;
  int64_t& iteration = collector_.iterations();
  while (num_timesteps_ < total_timesteps) {
    if (!collector_.collect(env, rollout_policy(), action_rng_, gamma_, gae_lambda_, hooks,
                            num_timesteps_))
      break;
    if (hooks.on_rollout_end) hooks.on_rollout_end(num_timesteps_);
    ++iteration;
    const double progress_remaining =
        1.0 - static_cast<double>(num_timesteps_) / static_cast<double>(total_timesteps);
    if (hooks.logger && iteration % log_interval == 0) {
      // SB3 OnPolicyAlgorithm._dump_logs, written before this iteration's train() as SB3 does.
      const double elapsed =
          std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      Logger& log = *hooks.logger;
      log.record("time/iterations", static_cast<double>(iteration));
      collector_.episode_stats().record(log);
      record_session_time(log, elapsed, num_timesteps_ - start_timesteps);
      log.record("time/total_timesteps", static_cast<double>(num_timesteps_));
      log.dump(num_timesteps_);
      if (hooks.on_log) hooks.on_log(num_timesteps_);
    }
    train(progress_remaining, hooks.logger);
    if (hooks.at_safe_point && !hooks.at_safe_point(num_timesteps_)) break;
  }
}

}  // namespace rlrun
