#include "rlrun/wrappers/normalize_observation.hpp"

#include <limits>

#include "rlrun/nn/policy_graph.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <utility>

namespace rlrun {

NormalizeObservation::NormalizeObservation(EnvPtr inner, const Config& config)
    : RunningStatisticsWrapper(std::move(inner)), config_(config) {
  const Space& inner_space = inner_->observation_space();
  // SB3 VecNormalize._sanity_checks: only Box observations (or Box keys of a Dict) can be
  // normalised.
  if (!inner_space.is_box() && !inner_space.is_dict())
    throw std::invalid_argument("NormalizeObservation needs a Box or Dict observation space, " +
                                inner_->id() + " has " + inner_space.describe());
  if (!(config_.clip_obs > 0))
    throw std::invalid_argument("NormalizeObservation: clip_obs must be > 0");
  if (!(config_.epsilon >= 0))
    throw std::invalid_argument("NormalizeObservation: epsilon must be >= 0");
  if (!inner_space.is_dict() && !config_.norm_obs_keys.empty())
    throw std::invalid_argument(
        "NormalizeObservation: norm_obs_keys needs a Dict observation space, " + inner_->id() +
        " has " + inner_space.describe());
  const float clip = static_cast<float>(config_.clip_obs);
  if (inner_space.is_box()) {
    space_ = Space::box(-clip, clip, inner_space.shape());
  } else {
    const std::vector<std::string>& keys = inner_space.keys();
    for (const std::string& key : config_.norm_obs_keys)
      if (std::find(keys.begin(), keys.end(), key) == keys.end())
        throw std::invalid_argument("NormalizeObservation: norm_obs_keys names '" + key +
                                    "', which is not a key of " + inner_space.describe());
    std::vector<std::pair<std::string, Space>> entries;
    for (size_t i = 0; i < keys.size(); ++i) {
      const Space& key_space = inner_space.subspaces()[i];
      const auto& listed = config_.norm_obs_keys;
      const bool chosen = listed.empty()
                              ? key_space.is_box()
                              : std::find(listed.begin(), listed.end(), keys[i]) != listed.end();
      if (chosen && !key_space.is_box())
        throw std::invalid_argument(
            "NormalizeObservation normalises Box keys only (SB3 "
            "VecNormalize), key '" +
            keys[i] + "' is " + key_space.describe());
      entries.emplace_back(keys[i],
                           chosen ? Space::box(-clip, clip, key_space.shape()) : key_space);
      if (!chosen) continue;
      for (int k = 0; k < key_space.flat_dim(); ++k) indices_.push_back(inner_space.offset(i) + k);
    }
    if (indices_.empty())
      throw std::invalid_argument("NormalizeObservation: " + inner_->id() + "'s " +
                                  inner_space.describe() + " has no Box key to normalise");
    space_ = Space::dict(std::move(entries));
    whole_ = false;
    picked_.resize(indices_.size());
  }
  rms_ = std::make_shared<RunningMeanStd>(whole_ ? inner_space.flat_dim()
                                                 : static_cast<int>(indices_.size()));
  original_.resize(inner_space.flat_dim());
  batch_scratch_.resize(2 * static_cast<size_t>(rms_->dim()));
}

void NormalizeObservation::update_batch(const Eigen::Ref<const Eigen::MatrixXf>& obs) {
  if (updating()) rms_->update_batch(obs, indices_, batch_scratch_);
}

std::span<const float> NormalizeObservation::selected(std::span<const float> obs) {
  if (whole_) return obs;
  for (size_t k = 0; k < indices_.size(); ++k) picked_[k] = obs[static_cast<size_t>(indices_[k])];
  return picked_;
}

void NormalizeObservation::reset(std::optional<uint64_t> seed, std::span<float> obs) {
  inner_->reset(seed, obs);
  std::copy(obs.begin(), obs.end(), original_.begin());
  if (batched_) return;
  if (updating()) rms_->update(selected(obs));  // VecNormalize.reset updates obs_rms
  normalize(obs);
}

StepResult NormalizeObservation::after_step(StepResult result, std::span<float> obs) {
  std::copy(obs.begin(), obs.end(), original_.begin());
  if (batched_) return result;
  if (updating() && !result.terminated && !result.truncated) rms_->update(selected(obs));
  normalize(obs);
  return result;
}

void NormalizeObservation::normalize(std::span<float> obs) const {
  const Eigen::VectorXd& mean = rms_->mean();
  const Eigen::VectorXd& var = rms_->var();
  for (Eigen::Index k = 0; k < mean.size(); ++k) {
    float& x = obs[whole_ ? static_cast<size_t>(k) : static_cast<size_t>(indices_[k])];
    const double z = (static_cast<double>(x) - mean[k]) / std::sqrt(var[k] + config_.epsilon);
    x = static_cast<float>(std::clamp(z, -config_.clip_obs, config_.clip_obs));
  }
}

std::string NormalizeObservation::export_observation(PolicyGraph& graph,
                                                     const std::string& obs) const {
  // normalize(): clip((x - mean) / sqrt(var + epsilon), +-clip_obs) on the normalised floats;
  // the others pass (shift 0, scale 1, unbounded).
  const int n = inner_->observation_space().flat_dim();
  constexpr float kInf = std::numeric_limits<float>::infinity();
  Eigen::VectorXf shift = Eigen::VectorXf::Zero(n), scale = Eigen::VectorXf::Ones(n);
  Eigen::VectorXf low = Eigen::VectorXf::Constant(n, -kInf),
                  high = Eigen::VectorXf::Constant(n, kInf);
  const Eigen::VectorXd& mean = rms_->mean();
  const Eigen::VectorXd& var = rms_->var();
  const float clip = static_cast<float>(config_.clip_obs);
  for (Eigen::Index k = 0; k < mean.size(); ++k) {
    const Eigen::Index i = whole_ ? k : indices_[static_cast<size_t>(k)];
    shift(i) = static_cast<float>(-mean[k]);
    scale(i) = static_cast<float>(1.0 / std::sqrt(var[k] + config_.epsilon));
    low(i) = -clip;
    high(i) = clip;
  }
  return graph.clamp(graph.affine(obs, shift, scale, Eigen::VectorXf::Zero(n)), low, high);
}

void NormalizeObservation::share_statistics_with(ModelStatistics& first) {
  auto* other = dynamic_cast<NormalizeObservation*>(&first);
  if (!other || other->rms_->dim() != rms_->dim())
    throw std::invalid_argument("NormalizeObservation: cannot share statistics with " +
                                first.statistics_name() + " of another shape");
  rms_ = other->rms_;
}

}  // namespace rlrun
