#include "rlrun/algos/ppo/ppo_loss.hpp"

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

}  // namespace rlrun
