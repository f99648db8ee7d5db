#include "rlrun/algos/ppo/ppo_loss.hpp"

#include "rlrun/algos/common/explained_variance.hpp"
#include "rlrun/algos/common/on_policy.hpp"

#include <algorithm>
#include <cmath>

namespace rlrun {

void normalize_advantages(Eigen::RowVectorXf& advantages) {
  const Eigen::Index n = advantages.size();
  if (n < 2) return;
  const float mean = advantages.mean();
  const float var = (advantages.array() - mean).square().sum() / static_cast<float>(n - 1);
  advantages = (advantages.array() - mean) / (std::sqrt(var) + 1e-8f);
}

PpoLossTerms ppo_loss(const PpoLossInputs& in, float clip_range, std::optional<float> clip_range_vf,
                      float ent_coef, float vf_coef, Eigen::RowVectorXf& grad_values,
                      Eigen::RowVectorXf& grad_log_prob, Eigen::RowVectorXf& grad_entropy) {
  const Eigen::Index batch = in.values.size();
  const float inv_batch = 1.0f / static_cast<float>(batch);
  PpoLossTerms t;
  double clipped = 0, entropy_sum = 0;
  for (Eigen::Index j = 0; j < batch; ++j) {
    const float log_ratio = in.log_prob(j) - in.old_log_prob(j);
    const float ratio = std::exp(log_ratio);
    const float adv = in.advantages(j);
    const float surrogate = adv * ratio;
    const float clipped_surrogate = adv * std::clamp(ratio, 1.0f - clip_range, 1.0f + clip_range);
    t.policy_loss -= std::min(surrogate, clipped_surrogate);
    // d(-min)/dlog_prob: the unclipped branch passes adv * ratio (dr/dlog_prob = r); where the
    // clipped branch is the smaller one the clamp is active and the gradient is zero.
    grad_log_prob(j) = surrogate <= clipped_surrogate ? -adv * ratio * inv_batch : 0.0f;
    clipped += std::abs(ratio - 1.0f) > clip_range;
    t.approx_kl += (ratio - 1.0f) - log_ratio;

    float value_pred = in.values(j);
    float value_gate = 1.0f;
    if (clip_range_vf) {
      const float delta = value_pred - in.old_values(j);
      const float clamped = std::clamp(delta, -*clip_range_vf, *clip_range_vf);
      value_gate = clamped == delta ? 1.0f : 0.0f;
      value_pred = in.old_values(j) + clamped;
    }
    const float error = value_pred - in.returns(j);
    t.value_loss += error * error;
    grad_values(j) = vf_coef * 2.0f * error * inv_batch * value_gate;
    entropy_sum += in.entropy(j);
    grad_entropy(j) = -ent_coef * inv_batch;
  }
  t.policy_loss *= inv_batch;
  t.value_loss *= inv_batch;
  t.approx_kl *= inv_batch;
  t.clip_fraction = clipped * inv_batch;
  t.entropy_loss = -entropy_sum * inv_batch;
  t.loss = t.policy_loss + ent_coef * t.entropy_loss + vf_coef * t.value_loss;
  return t;
}

void record_ppo_statistics(Logger& logger, const PpoTrainStatistics& s,
                           const RolloutBuffer& rollout, const ActorCriticPolicy& policy,
                           int64_t n_updates, float lr, float clip_range,
                           std::optional<float> clip_range_vf) {
  const double n = std::max(s.n_minibatches, 1);
  logger.record("train/entropy_loss", s.entropy_loss_sum / n);
  logger.record("train/policy_gradient_loss", s.pg_loss_sum / n);
  logger.record("train/value_loss", s.value_loss_sum / n);
  logger.record("train/approx_kl", s.approx_kl_count ? s.approx_kl_sum / s.approx_kl_count : 0.0);
  logger.record("train/clip_fraction", s.clip_fraction_sum / n);
  logger.record("train/loss", s.last_loss);
  // Flattened in SB3's order (rollout_buffer.values.flatten(): step by step, the envs of a
  // step in turn), which is also the buffer's storage order, so the sums read memory in line.
  logger.record("train/explained_variance",
                explained_variance(rollout.values.reshaped<Eigen::RowMajor>(),
                                   rollout.returns.reshaped<Eigen::RowMajor>()));
  if (policy.gaussian()) logger.record("train/std", policy.mean_std());
  logger.record("train/n_updates", static_cast<double>(n_updates));
  logger.record("train/clip_range", clip_range);
  if (clip_range_vf) logger.record("train/clip_range_vf", *clip_range_vf);
  logger.record("train/learning_rate", lr);
}

}  // namespace rlrun
