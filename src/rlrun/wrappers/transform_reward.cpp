#include "rlrun/wrappers/transform_reward.hpp"

#include <algorithm>
#include <stdexcept>

namespace rlrun {

TransformReward::TransformReward(EnvPtr inner, const Config& config)
    : Wrapper(std::move(inner)), config_(config) {
  if (config_.clip_min && config_.clip_max && *config_.clip_min > *config_.clip_max)
    throw std::invalid_argument("TransformReward: clip_min must not exceed clip_max");
}

StepResult TransformReward::step(std::span<const float> action, std::span<float> obs) {
  return transform(inner_->step(action, obs));
}

StepResult TransformReward::transform(StepResult result) const {
  double r = result.reward;
  if (config_.sign) r = r > 0.0 ? 1.0 : r < 0.0 ? -1.0 : r;  // np.sign: 0 (and NaN) stay
  r = config_.scale * r + config_.offset;
  if (config_.clip_min) r = std::max(r, *config_.clip_min);
  if (config_.clip_max) r = std::min(r, *config_.clip_max);
  result.reward = r;
  return result;
}

}  // namespace rlrun
