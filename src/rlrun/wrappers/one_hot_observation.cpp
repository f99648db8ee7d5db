#include "rlrun/wrappers/one_hot_observation.hpp"

#include <stdexcept>

namespace rlrun {

OneHotObservation::OneHotObservation(EnvPtr inner, const Config&) : Wrapper(std::move(inner)) {
  const Space& s = inner_->observation_space();
  if (s.is_box() || s.is_dict())
    throw std::invalid_argument(
        "OneHotObservation needs a Discrete, MultiDiscrete or MultiBinary observation space, " +
        inner_->id() + " has " + s.describe() +
        (s.is_dict() ? " (PPO and A2C take Dict observations as they are)" : ""));
  encoder_ = ObservationEncoder(s);
  space_ = Space::box(0.0f, 1.0f, {encoder_.features_dim()});
  inner_obs_.assign(static_cast<size_t>(s.flat_dim()), 0.0f);
}

void OneHotObservation::encode(std::span<float> obs) const {
  try {
    encoder_.encode_sample(inner_obs_, obs);
  } catch (const std::out_of_range& e) {
    throw std::out_of_range(inner_->id() + ": " + e.what());
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
  encoder_.decode_sample(obs, inner);
  return inner_->render_observation(inner, frame);
}

}  // namespace rlrun
