#include "rlrun/wrappers/grayscale_observation.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "rlrun/env/image_space.hpp"
#include "rlrun/render/draw_pixels.hpp"
#include "rlrun/wrappers/opencv_image_ops.hpp"

namespace rlrun {

GrayscaleObservation::GrayscaleObservation(EnvPtr inner, const Config& config)
    : Wrapper(std::move(inner)) {
  const Space& s = inner_->observation_space();
  // gymnasium/wrappers/transform_observation.py GrayscaleObservation's assertions.
  const bool image = s.shape().size() == 3 && s.shape()[2] == 3 && is_pixel_box(s);
  if (!image)
    throw std::invalid_argument(
        "GrayscaleObservation needs an RGB image observation, Box(0, 255, "
        "(height, width, 3), uint8); " +
        inner_->id() + " has " + s.describe());
  if (config.weights != "gymnasium" && config.weights != "opencv")
    throw std::invalid_argument(
        "GrayscaleObservation: weights must be 'gymnasium' or 'opencv', not '" + config.weights +
        "'");
  opencv_weights_ = config.weights == "opencv";
  height_ = s.shape()[0];
  width_ = s.shape()[1];
  space_ = config.keep_dim ? Space::image({height_, width_, 1}) : Space::image({height_, width_});
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
  if (opencv_weights_) {
    for (size_t p = 0; p < pixels; ++p)
      obs[p] = opencv_rgb_to_gray(opencv_pixel(rgb_[3 * p]), opencv_pixel(rgb_[3 * p + 1]),
                                  opencv_pixel(rgb_[3 * p + 2]));
    return;
  }
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
  draw_pixels(obs, height_, width_, 1, frame);
  return true;
}

}  // namespace rlrun
