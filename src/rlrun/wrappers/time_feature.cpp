#include "rlrun/wrappers/time_feature.hpp"

#include <algorithm>
#include <stdexcept>

#include "rlrun/wrappers/time_limit.hpp"

namespace rlrun {

TimeFeature::TimeFeature(EnvPtr inner, const Config& config)
    : Wrapper(std::move(inner)), config_(config), max_steps_(config.max_steps) {
  const Space& s = inner_->observation_space();
  if (!s.is_box() || s.shape().size() != 1)
    throw std::invalid_argument("TimeFeature needs a 1-D Box observation space, " + inner_->id() +
                                " has " + s.describe());
  std::vector<float> low = s.low(), high = s.high();
  low.push_back(0.0f);
  high.push_back(1.0f);
  space_ = Space::box(std::move(low), std::move(high));
  // sb3_contrib: env.spec.max_episode_steps when there is one, else the max_steps argument.
  for (Env* e = inner_.get(); auto* w = dynamic_cast<Wrapper*>(e); e = &w->inner())
    if (auto* limit = dynamic_cast<TimeLimit*>(w)) {
      max_steps_ = limit->max_episode_steps();
      break;
    }
  inner_obs_.resize(static_cast<size_t>(s.flat_dim()));
}

void TimeFeature::reset(std::optional<uint64_t> seed, std::span<float> obs) {
  current_step_ = 0;
  inner_->reset(seed, std::span<float>(inner_obs_));
  append_feature(obs);
}

StepResult TimeFeature::step(std::span<const float> action, std::span<float> obs) {
  ++current_step_;
  const StepResult result = inner_->step(action, std::span<float>(inner_obs_));
  append_feature(obs);
  return result;
}

void TimeFeature::append_feature(std::span<float> obs) {
  std::copy(inner_obs_.begin(), inner_obs_.end(), obs.begin());
  // float64 arithmetic, then the observation dtype (np.array(time_feature, dtype=self.dtype)).
  const double feature =
      config_.test_mode ? 1.0 : 1.0 - static_cast<double>(current_step_) / max_steps_;
  obs[inner_obs_.size()] = static_cast<float>(feature);
}

}  // namespace rlrun
