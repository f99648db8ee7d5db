#include "rlrun/wrappers/one_hot_observation.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>

namespace rlrun {

OneHotObservation::OneHotObservation(EnvPtr inner, const Config&) : Wrapper(std::move(inner)) {
  const Space& s = inner_->observation_space();
  switch (s.kind()) {
    case SpaceKind::kDiscrete:
      sizes_ = {s.n()};
      starts_ = {s.start()};
      break;
    case SpaceKind::kMultiDiscrete:
      sizes_ = s.nvec();
      starts_.assign(sizes_.size(), 0);
      break;
    case SpaceKind::kMultiBinary:
      // A bit is passed through as one float (SB3: obs.float()), marked by size 1.
      sizes_.assign(static_cast<size_t>(s.flat_dim()), 1);
      starts_.assign(sizes_.size(), 0);
      break;
    case SpaceKind::kBox:
      throw std::invalid_argument(
          "OneHotObservation needs a Discrete, MultiDiscrete or "
          "MultiBinary observation space, " +
          inner_->id() + " has " + s.describe());
  }
  const int64_t total = std::accumulate(sizes_.begin(), sizes_.end(), int64_t{0});
  space_ = Space::box(0.0f, 1.0f, {static_cast<int>(total)});
  inner_obs_.assign(static_cast<size_t>(s.flat_dim()), 0.0f);
}

void OneHotObservation::encode(std::span<float> obs) const {
  std::fill(obs.begin(), obs.end(), 0.0f);
  const bool bits = inner_->observation_space().kind() == SpaceKind::kMultiBinary;
  size_t offset = 0;
  for (size_t i = 0; i < sizes_.size(); ++i) {
    if (bits) {
      obs[offset] = inner_obs_[i];
    } else {
      const int64_t index = static_cast<int64_t>(std::lround(inner_obs_[i])) - starts_[i];
      if (index < 0 || index >= sizes_[i])
        throw std::out_of_range(inner_->id() + ": observation entry " + std::to_string(i) +
                                " is outside " + inner_->observation_space().describe());
      obs[offset + static_cast<size_t>(index)] = 1.0f;
    }
    offset += static_cast<size_t>(sizes_[i]);
  }
}

void OneHotObservation::reset(std::optional<uint64_t> seed, std::span<float> obs) {
  inner_->reset(seed, inner_obs_);
  encode(obs);
}

StepResult OneHotObservation::step(std::span<const float> action, std::span<float> obs) {
  const StepResult result = inner_->step(action, inner_obs_);
  encode(obs);
  return result;
}

bool OneHotObservation::render_observation(std::span<const float> obs, Frame& frame) const {
  std::vector<float> inner(inner_obs_.size());
  const bool bits = inner_->observation_space().kind() == SpaceKind::kMultiBinary;
  size_t offset = 0;
  for (size_t i = 0; i < sizes_.size(); ++i) {
    if (bits) {
      inner[i] = obs[offset];
    } else {
      const auto begin = obs.begin() + static_cast<std::ptrdiff_t>(offset);
      const auto hot = std::max_element(begin, begin + static_cast<std::ptrdiff_t>(sizes_[i]));
      inner[i] = static_cast<float>(starts_[i] + (hot - begin));
    }
    offset += static_cast<size_t>(sizes_[i]);
  }
  return inner_->render_observation(inner, frame);
}

}  // namespace rlrun
