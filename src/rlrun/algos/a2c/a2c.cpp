#include "rlrun/algos/a2c/a2c.hpp"

#include <cmath>
#include <stdexcept>

#include "rlrun/algos/common/explained_variance.hpp"
#include "rlrun/algos/ppo/ppo_loss.hpp"
#include "rlrun/core/config_validation.hpp"
#include "rlrun/nn/clip_grad.hpp"

namespace rlrun {

ConfigProblems A2C::check(const Config& config, const AlgorithmSetup& setup) {
  const int64_t rollout = static_cast<int64_t>(config.n_steps) * setup.n_envs;
  ConfigProblems out = check_actor_critic(config.policy, rollout, rollout, setup);
  check_use_sde(out, config.use_sde, setup);
  return out;
}

A2C::A2C(const Config& config, const AlgorithmSetup& setup)
    : OnPolicyAlgorithm("A2C", setup, valid_config(config, "A2C").policy,
                        {config.n_steps, config.gamma, config.gae_lambda, config.use_sde,
                         config.sde_sample_freq}),
      config_(config) {
  if (config_.use_rms_prop) {
    // SB3 A2C: RMSprop(alpha=0.99, eps=rms_prop_eps, weight_decay=0).
    RmsPropConfig rms;
    rms.alpha = 0.99;
    rms.eps = config_.rms_prop_eps;
    checkpoint("optimizer", rmsprop_.emplace(policy_.param_blocks(), rms));
  } else {
    AdamConfig adam;
    adam.eps = 1e-5;  // SB3 ActorCriticPolicy's Adam eps
    checkpoint("optimizer", adam_.emplace(policy_.param_blocks(), adam));
  }
  const int size = config_.n_steps * setup.n_envs;
  for (Eigen::RowVectorXf* v :
       {&advantages_, &returns_, &grad_values_, &grad_log_prob_, &grad_entropy_})
    v->resize(size);
}

void A2C::train(double progress_remaining, Logger* logger) {
  const float lr = static_cast<float>(config_.learning_rate(progress_remaining));
  const RolloutBuffer& rollout = collector_.buffer();
  // One step on the whole rollout (SB3 rollout_buffer.get(batch_size=None)); the sample order
  // does not matter for a full-batch mean.
  obs_.resize(rollout.obs.rows(), rollout.size());
  for (int k = 0; k < rollout.size(); ++k) rollout.obs.get(k, obs_.col(k).data());
  policy_.evaluate_actions(obs_, rollout.actions, values_, log_prob_, entropy_);
  advantages_ = rollout.advantages.reshaped<Eigen::RowMajor>().transpose();
  returns_ = rollout.returns.reshaped<Eigen::RowMajor>().transpose();
  if (config_.normalize_advantage) normalize_advantages(advantages_);

  const Eigen::Index n = values_.size();
  const float inv_n = 1.0f / static_cast<float>(n);
  const float vf_coef = static_cast<float>(config_.vf_coef);
  const float ent_coef = static_cast<float>(config_.ent_coef);
  double policy_loss = 0, value_loss = 0, entropy_sum = 0;
  for (Eigen::Index j = 0; j < n; ++j) {
    policy_loss -= advantages_(j) * log_prob_(j);
    grad_log_prob_(j) = -advantages_(j) * inv_n;
    const float error = values_(j) - returns_(j);
    value_loss += error * error;
    grad_values_(j) = vf_coef * 2.0f * error * inv_n;
    entropy_sum += entropy_(j);
    grad_entropy_(j) = -ent_coef * inv_n;
  }
  policy_loss *= inv_n;
  value_loss *= inv_n;
  const double entropy_loss = -entropy_sum * inv_n;

  policy_.zero_grad();
  policy_.backward(grad_values_, grad_log_prob_, grad_entropy_);
  std::vector<ParamBlock> blocks = policy_.param_blocks();
  clip_grad_norm(blocks, static_cast<float>(config_.max_grad_norm));
  if (rmsprop_)
    rmsprop_->step(lr);
  else
    adam_->step(lr);
  ++n_updates_;

  if (!logger) return;
  logger->record("train/n_updates", static_cast<double>(n_updates_));
  // Flattened in SB3's order (rollout_buffer.values.flatten(): step by step, the envs of a
  // step in turn), which is also the buffer's storage order, so the sums read memory in line.
  logger->record("train/explained_variance",
                 explained_variance(rollout.values.reshaped<Eigen::RowMajor>(),
                                    rollout.returns.reshaped<Eigen::RowMajor>()));
  logger->record("train/entropy_loss", entropy_loss);
  logger->record("train/policy_loss", policy_loss);
  logger->record("train/value_loss", value_loss);
  logger->record("train/learning_rate", lr);
  if (policy_.gaussian()) logger->record("train/std", policy_.mean_std());
}

}  // namespace rlrun
