#include "rlrun/wrappers/grayscale_observation.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "rlrun/frame.hpp"

namespace rlrun {

GrayscaleObservation::GrayscaleObservation(EnvPtr inner, const Config& config)
    : Wrapper(std::move(inner)) {
  const Space& s = inner_->observation_space();
  const bool image =
      s.is_box() && s.shape().size() == 3 && s.shape()[2] == 3 &&
      std::all_of(s.low().begin(), s.low().end(), [](float v) { return v == 0; }) &&
      std::all_of(s.high().begin(), s.high().end(), [](float v) { return v == 255; });
  if (!image)
    throw std::invalid_argument(
        "GrayscaleObservation needs an RGB image observation, Box(0, 255, "
        "(height, width, 3)); " +
        inner_->id() + " has " + s.describe());
  height_ = s.shape()[0];
  width_ = s.shape()[1];
  space_ = config.keep_dim ? Space::box(0.0f, 255.0f, {height_, width_, 1})
                           : Space::box(0.0f, 255.0f, {height_, width_});
  rgb_.resize(static_cast<size_t>(s.flat_dim()));
}

float GrayscaleObservation::gray(float r, float g, float b) {
  // numpy: uint8 * float64 weights, a sum over the last axis from the first element, then a
  // cast to uint8 (truncation; the sum never leaves [0, 256)).
  const double sum = static_cast<double>(r) * 0.2125 + static_cast<double>(g) * 0.7154 +
                     static_cast<double>(b) * 0.0721;
  return static_cast<float>(std::trunc(std::clamp(sum, 0.0, 255.0)));
}

void GrayscaleObservation::convert(std::span<float> obs) const {
  const size_t pixels = static_cast<size_t>(height_) * width_;
  for (size_t p = 0; p < pixels; ++p) obs[p] = gray(rgb_[3 * p], rgb_[3 * p + 1], rgb_[3 * p + 2]);
}

void GrayscaleObservation::reset(std::optional<uint64_t> seed, std::span<float> obs) {
  inner_->reset(seed, rgb_);
  convert(obs);
}

StepResult GrayscaleObservation::step(std::span<const float> action, std::span<float> obs) {
  const StepResult result = inner_->step(action, rgb_);
  convert(obs);
  return result;
}

bool GrayscaleObservation::render_observation(std::span<const float> obs, Frame& frame) const {
  uint32_t* out = frame.pixels();
  for (int y = 0; y < frame.height(); ++y) {
    const int sy = std::min(height_ - 1, static_cast<int>(int64_t{y} * height_ / frame.height()));
    for (int x = 0; x < frame.width(); ++x) {
      const int sx = std::min(width_ - 1, static_cast<int>(int64_t{x} * width_ / frame.width()));
      const auto v = static_cast<uint32_t>(std::clamp(obs[size_t(sy) * width_ + sx], 0.0f, 255.0f));
      out[size_t(y) * frame.stride_pixels() + x] = v << 16 | v << 8 | v;
    }
  }
  return true;
}

}  // namespace rlrun
