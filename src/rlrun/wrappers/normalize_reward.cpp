#include "rlrun/wrappers/normalize_reward.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace rlrun {

NormalizeReward::NormalizeReward(EnvPtr inner, const Config& config)
    : RunningStatisticsWrapper(std::move(inner)), config_(config) {
  rms_ = std::make_shared<RunningMeanStd>(1);
  if (!(config_.gamma >= 0 && config_.gamma <= 1))
    throw std::invalid_argument("NormalizeReward: gamma must be in [0, 1]");
  if (!(config_.clip_reward > 0))
    throw std::invalid_argument("NormalizeReward: clip_reward must be > 0");
  if (!(config_.epsilon >= 0)) throw std::invalid_argument("NormalizeReward: epsilon must be >= 0");
}

void NormalizeReward::reset(std::optional<uint64_t> seed, std::span<float> obs) {
  inner_->reset(seed, obs);
  if (!batched_) return_ = 0.0;  // VecNormalize.reset: self.returns = np.zeros(num_envs)
}

StepResult NormalizeReward::after_step(StepResult result, std::span<float> /*obs*/) {
  if (batched_) return result;
  if (training_) rms_->update(add_to_return(result.reward));  // VecNormalize._update_reward
  result.reward = scale(result.reward);
  if (result.terminated || result.truncated) return_ = 0.0;  // self.returns[dones] = 0
  return result;
}

double NormalizeReward::add_to_return(double reward) {
  if (training_) return_ = return_ * config_.gamma + reward;
  return return_;
}

void NormalizeReward::update_batch(std::span<const double> returns, std::span<double> scratch) {
  if (training_) rms_->update_batch(returns, scratch);
}

double NormalizeReward::scale(double reward) const {
  if (!training_ && unscaled_when_frozen_) return reward;
  return std::clamp(reward / std::sqrt(rms_->var()[0] + config_.epsilon), -config_.clip_reward,
                    config_.clip_reward);
}

void NormalizeReward::share_statistics_with(ModelStatistics& first) {
  auto* other = dynamic_cast<NormalizeReward*>(&first);
  if (!other)
    throw std::invalid_argument("NormalizeReward: cannot share statistics with " +
                                first.statistics_name());
  rms_ = other->rms_;
}

void NormalizeReward::write_own_state(StateWriter& out) const {
  StateWriter own = out.sub("normalize_reward");
  rms_->write(own);
  own.put_double("return", return_);
}

void NormalizeReward::read_own_state(const StateReader& in) {
  const StateReader own = in.sub("normalize_reward");
  rms_->read(own);
  return_ = own.get_double("return");
}

}  // namespace rlrun
