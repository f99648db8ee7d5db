#include "rlrun/algos/ppo/ppo.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <numeric>
#include <stdexcept>

#include "rlrun/algos/common/episode_stats.hpp"
#include "rlrun/algos/common/explained_variance.hpp"
#include "rlrun/algos/ppo/ppo_loss.hpp"
#include "rlrun/env/vec_env.hpp"
#include "rlrun/nn/clip_grad.hpp"

namespace rlrun {

namespace {
// Distinct streams from one seed: weights, action sampling, minibatch shuffling.
constexpr uint64_t kActionStream = 0x5851f42d4c957f2dULL;
constexpr uint64_t kShuffleStream = 0x14057b7ef767814fULL;
}  // namespace

PPO::PPO(const Config& config, const AlgorithmSetup& setup)
    : config_(config),
      setup_(setup),
      init_rng_(setup.seed),
      action_rng_(setup.seed ^ kActionStream),
      shuffle_rng_(setup.seed ^ kShuffleStream),
      policy_(setup.observation_space, setup.action_space, config.policy, init_rng_) {
  if (config_.n_steps < 1) throw std::invalid_argument("PPO: n_steps must be >= 1");
  if (config_.batch_size < 2)
    throw std::invalid_argument("PPO: batch_size must be > 1 (advantage normalisation)");
  if (config_.n_epochs < 1) throw std::invalid_argument("PPO: n_epochs must be >= 1");
  // SB3 ActorCriticPolicy: Adam with eps=1e-5 "to avoid NaN".
  AdamConfig adam;
  adam.eps = 1e-5;
  optimizer_ = Adam(policy_.param_blocks(), adam);

  const int obs_dim = setup.observation_space.flat_dim();
  const int n_envs = setup.n_envs;
  const int size = config_.n_steps * n_envs;
  obs_buf_.resize(obs_dim, size);
  act_buf_.resize(policy_.action_dim(), size);
  for (StepEnvMatrix* m : {&rewards_, &values_, &episode_starts_, &log_probs_, &advantages_, &returns_})
    m->resize(config_.n_steps, n_envs);
  last_obs_.resize(obs_dim, n_envs);
  last_episode_starts_ = Eigen::RowVectorXf::Ones(n_envs);
  env_actions_.resize(setup.action_space.flat_dim(), n_envs);
  final_obs_col_.resize(obs_dim, 1);
  indices_.resize(size);
  const int batch = std::min(config_.batch_size, size);
  mb_obs_.resize(obs_dim, batch);
  mb_act_.resize(policy_.action_dim(), batch);
  for (Eigen::RowVectorXf* v : {&mb_adv_, &mb_ret_, &mb_old_logp_, &mb_old_val_, &values_pred_,
                                &grad_values_, &grad_log_prob_, &grad_entropy_})
    v->resize(batch);
}

void PPO::clip_to_action_space(Eigen::MatrixXf& actions) const {
  // SB3 clips Box actions to the bounds before env.step (the buffer keeps the unclipped ones).
  const Space& space = setup_.action_space;
  if (!space.is_box()) return;
  for (Eigen::Index j = 0; j < actions.cols(); ++j)
    for (Eigen::Index i = 0; i < actions.rows(); ++i)
      actions(i, j) = std::clamp(actions(i, j), space.low()[i], space.high()[i]);
}

void PPO::predict(const Eigen::Ref<const Eigen::MatrixXf>& obs, bool deterministic,
                  Eigen::MatrixXf& actions) {
  policy_.act(obs, action_rng_, deterministic, actions, step_values_, step_log_probs_);
  clip_to_action_space(actions);
}

bool PPO::collect_rollouts(VecEnv& env, TrainingHooks& hooks) {
  const int n_envs = env.num_envs();
  const float gamma = static_cast<float>(config_.gamma);
  for (int step = 0; step < config_.n_steps; ++step) {
    policy_.act(last_obs_, action_rng_, false, step_actions_, step_values_, step_log_probs_);
    env_actions_ = step_actions_;
    clip_to_action_space(env_actions_);
    env.step(env_actions_);
    num_timesteps_ += n_envs;
    if (hooks.on_step && !hooks.on_step(num_timesteps_)) return false;
    episode_stats_.update(env);

    for (int e = 0; e < n_envs; ++e) {
      float reward = static_cast<float>(env.rewards()(e));
      // Timeout bootstrap (SB3 on_policy_algorithm.py): a truncated, non-terminal step gets
      // gamma * V(final_obs) added to its reward, since GAE then treats it as an episode end.
      if (env.truncated(e) && !env.terminated(e)) {
        final_obs_col_ = env.final_obs().col(e);
        policy_.predict_values(final_obs_col_, terminal_value_);
        reward += gamma * terminal_value_(0);
      }
      const int k = step * n_envs + e;
      obs_buf_.col(k) = last_obs_.col(e);
      act_buf_.col(k) = step_actions_.col(e);
      rewards_(step, e) = reward;
      episode_starts_(step, e) = last_episode_starts_(e);
      values_(step, e) = step_values_(e);
      log_probs_(step, e) = step_log_probs_(e);
      last_episode_starts_(e) = env.done(e) ? 1.0f : 0.0f;
    }
    last_obs_ = env.obs();
  }
  policy_.predict_values(last_obs_, terminal_value_);
  compute_gae(rewards_, values_, episode_starts_, terminal_value_, last_episode_starts_, gamma,
              static_cast<float>(config_.gae_lambda), advantages_, returns_);
  return true;
}

void PPO::train(Logger* logger) {
  const float lr = static_cast<float>(config_.learning_rate(progress_remaining_));
  const float clip_range = static_cast<float>(config_.clip_range(progress_remaining_));
  std::optional<float> clip_range_vf;
  if (config_.clip_range_vf)
    clip_range_vf = static_cast<float>((*config_.clip_range_vf)(progress_remaining_));
  const float ent_coef = static_cast<float>(config_.ent_coef);
  const float vf_coef = static_cast<float>(config_.vf_coef);
  const int size = static_cast<int>(indices_.size());

  double entropy_loss_sum = 0, pg_loss_sum = 0, value_loss_sum = 0, clip_fraction_sum = 0;
  int n_minibatches = 0;
  double last_loss = 0, approx_kl_sum = 0;
  int approx_kl_count = 0;
  bool continue_training = true;
  std::vector<ParamBlock> blocks = policy_.param_blocks();

  for (int epoch = 0; epoch < config_.n_epochs && continue_training; ++epoch) {
    approx_kl_sum = 0;
    approx_kl_count = 0;
    // np.random.permutation: Fisher-Yates with the run's RNG.
    std::iota(indices_.begin(), indices_.end(), 0);
    for (int i = size - 1; i > 0; --i)
      std::swap(indices_[i], indices_[static_cast<int>(shuffle_rng_.below(i + 1))]);

    for (int start = 0; start < size; start += config_.batch_size) {
      const int batch = std::min(config_.batch_size, size - start);
      if (mb_obs_.cols() != batch) {
        mb_obs_.resize(Eigen::NoChange, batch);
        mb_act_.resize(Eigen::NoChange, batch);
        for (Eigen::RowVectorXf* v : {&mb_adv_, &mb_ret_, &mb_old_logp_, &mb_old_val_,
                                      &values_pred_, &grad_values_, &grad_log_prob_, &grad_entropy_})
          v->resize(batch);
      }
      for (int j = 0; j < batch; ++j) {
        const int k = indices_[start + j];
        mb_obs_.col(j) = obs_buf_.col(k);
        mb_act_.col(j) = act_buf_.col(k);
        mb_adv_(j) = advantages_.data()[k];
        mb_ret_(j) = returns_.data()[k];
        mb_old_logp_(j) = log_probs_.data()[k];
        mb_old_val_(j) = values_.data()[k];
      }
      policy_.evaluate_actions(mb_obs_, mb_act_, values_pred_, log_prob_, entropy_);

      if (config_.normalize_advantage) normalize_advantages(mb_adv_);
      const PpoLossTerms t = ppo_loss({values_pred_, log_prob_, entropy_, mb_old_logp_,
                                       mb_old_val_, mb_adv_, mb_ret_},
                                      clip_range, clip_range_vf, ent_coef, vf_coef, grad_values_,
                                      grad_log_prob_, grad_entropy_);
      pg_loss_sum += t.policy_loss;
      value_loss_sum += t.value_loss;
      entropy_loss_sum += t.entropy_loss;
      clip_fraction_sum += t.clip_fraction;
      approx_kl_sum += t.approx_kl;
      ++approx_kl_count;
      ++n_minibatches;
      last_loss = t.loss;

      if (config_.target_kl && t.approx_kl > 1.5 * *config_.target_kl) {
        continue_training = false;
        break;
      }
      policy_.zero_grad();
      policy_.backward(grad_values_, grad_log_prob_, grad_entropy_);
      clip_grad_norm(blocks, static_cast<float>(config_.max_grad_norm));
      optimizer_.step(lr);
    }
    ++n_updates_;
  }

  if (!logger) return;
  const double n = std::max(n_minibatches, 1);
  logger->record("train/entropy_loss", entropy_loss_sum / n);
  logger->record("train/policy_gradient_loss", pg_loss_sum / n);
  logger->record("train/value_loss", value_loss_sum / n);
  logger->record("train/approx_kl", approx_kl_count ? approx_kl_sum / approx_kl_count : 0.0);
  logger->record("train/clip_fraction", clip_fraction_sum / n);
  logger->record("train/loss", last_loss);
  logger->record("train/explained_variance",
                 explained_variance(values_.reshaped(), returns_.reshaped()));
  if (!policy_.discrete()) logger->record("train/std", policy_.mean_std());
  logger->record("train/n_updates", static_cast<double>(n_updates_));
  logger->record("train/clip_range", clip_range);
  if (clip_range_vf) logger->record("train/clip_range_vf", *clip_range_vf);
  logger->record("train/learning_rate", lr);
}

void PPO::learn(VecEnv& env, int64_t total_timesteps, TrainingHooks& hooks) {
  if (env.num_envs() != setup_.n_envs)
    throw std::invalid_argument("PPO: env has " + std::to_string(env.num_envs()) +
                                " copies, the algorithm was built for " +
                                std::to_string(setup_.n_envs));
  const auto start = std::chrono::steady_clock::now();
  const int64_t start_timesteps = num_timesteps_;
  last_obs_ = env.reset();
  last_episode_starts_.setOnes();
  int64_t iteration = 0;
  while (num_timesteps_ < total_timesteps) {
    if (!collect_rollouts(env, hooks)) break;
    ++iteration;
    progress_remaining_ = 1.0 - static_cast<double>(num_timesteps_) / static_cast<double>(total_timesteps);
    const int log_interval = hooks.log_interval > 0 ? hooks.log_interval : 1;
    if (hooks.logger && iteration % log_interval == 0) {
      // SB3 OnPolicyAlgorithm._dump_logs, written before this iteration's train() as SB3 does.
      const double elapsed =
          std::max(1e-9, std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
      Logger& log = *hooks.logger;
      log.record("time/iterations", static_cast<double>(iteration));
      episode_stats_.record(log);
      log.record("time/fps", std::floor(static_cast<double>(num_timesteps_ - start_timesteps) / elapsed));
      log.record("time/time_elapsed", std::floor(elapsed));
      log.record("time/total_timesteps", static_cast<double>(num_timesteps_));
      log.dump(num_timesteps_);
      if (hooks.on_log) hooks.on_log(num_timesteps_);
    }
    train(hooks.logger);
  }
}

void PPO::save(TensorMap& tensors) const { policy_.save(tensors); }
void PPO::load(const TensorMap& tensors) { policy_.load(tensors); }

}  // namespace rlrun
