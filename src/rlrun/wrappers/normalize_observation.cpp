#include "rlrun/wrappers/normalize_observation.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace rlrun {

NormalizeObservation::NormalizeObservation(EnvPtr inner, const Config& config)
    : Wrapper(std::move(inner)), config_(config) {
  const Space& inner_space = inner_->observation_space();
  // SB3 VecNormalize._sanity_checks: only Box observations can be normalised.
  if (!inner_space.is_box())
    throw std::invalid_argument("NormalizeObservation needs a Box observation space, " +
                                inner_->id() + " has " + inner_space.describe());
  if (!(config_.clip_obs > 0)) throw std::invalid_argument("NormalizeObservation: clip_obs must be > 0");
  if (!(config_.epsilon >= 0)) throw std::invalid_argument("NormalizeObservation: epsilon must be >= 0");
  const float clip = static_cast<float>(config_.clip_obs);
  space_ = Space::box(-clip, clip, inner_space.shape());
  rms_ = std::make_shared<RunningMeanStd>(inner_space.flat_dim());
  original_.resize(inner_space.flat_dim());
}

void NormalizeObservation::reset(std::optional<uint64_t> seed, std::span<float> obs) {
  inner_->reset(seed, obs);
  std::copy(obs.begin(), obs.end(), original_.begin());
  if (training_) rms_->update(obs);  // VecNormalize.reset updates obs_rms
  normalize(obs);
}

StepResult NormalizeObservation::step(std::span<const float> action, std::span<float> obs) {
  const StepResult result = inner_->step(action, obs);
  std::copy(obs.begin(), obs.end(), original_.begin());
  if (training_ && !result.terminated && !result.truncated) rms_->update(obs);
  normalize(obs);
  return result;
}

void NormalizeObservation::normalize(std::span<float> obs) const {
  const Eigen::VectorXd& mean = rms_->mean();
  const Eigen::VectorXd& var = rms_->var();
  for (size_t i = 0; i < obs.size(); ++i) {
    const double z = (static_cast<double>(obs[i]) - mean[static_cast<Eigen::Index>(i)]) /
                     std::sqrt(var[static_cast<Eigen::Index>(i)] + config_.epsilon);
    obs[i] = static_cast<float>(std::clamp(z, -config_.clip_obs, config_.clip_obs));
  }
}

void NormalizeObservation::share_statistics_with(ModelStatistics& first) {
  auto* other = dynamic_cast<NormalizeObservation*>(&first);
  if (!other || other->rms_->dim() != rms_->dim())
    throw std::invalid_argument("NormalizeObservation: cannot share statistics with " +
                                first.statistics_name() + " of another shape");
  rms_ = other->rms_;
}

}  // namespace rlrun
