#include "rlrun/wrappers/resize_observation.hpp"

#include <algorithm>
#include <stdexcept>

#include "rlrun/env/image_space.hpp"
#include "rlrun/render/draw_pixels.hpp"

namespace rlrun {

void decode(const ConfigNode& n, ResizeShape& out) {
  if (n.is_sequence()) {
    if (n.size() != 2) n.fail("expected [height, width] or one number");
    out.height = static_cast<int>(n.at(0).as_int());
    out.width = static_cast<int>(n.at(1).as_int());
  } else {
    out.height = out.width = static_cast<int>(n.as_int());
  }
  // Gymnasium asserts positive sides; 4096 keeps a typo from allocating gigabytes per step.
  if (out.height < 1 || out.width < 1 || out.height > 4096 || out.width > 4096)
    n.fail("each side must be in [1, 4096]");
}

YAML::Node encode(const ResizeShape& shape) {
  YAML::Node n(YAML::NodeType::Sequence);
  n.push_back(shape.height);
  n.push_back(shape.width);
  n.SetStyle(YAML::EmitterStyle::Flow);
  return n;
}

ResizeObservation::ResizeObservation(EnvPtr inner, const Config& config)
    : Wrapper(std::move(inner)), height_(config.shape.height), width_(config.shape.width) {
  const Space& s = inner_->observation_space();
  const bool image = (s.shape().size() == 2 || s.shape().size() == 3) && is_pixel_box(s);
  if (!image)
    throw std::invalid_argument(
        "ResizeObservation needs an image observation, Box(0, 255, (height, width), uint8) or "
        "(height, width, channels); " +
        inner_->id() + " has " + s.describe());
  from_ = {s.shape()[0], s.shape()[1], s.shape().size() == 3 ? s.shape()[2] : 1};
  try {
    resize_ = OpencvAreaResize(from_, height_, width_);
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument(std::string("ResizeObservation: ") + e.what());
  }
  std::vector<int> shape{height_, width_};
  if (s.shape().size() == 3) shape.push_back(from_.channels);
  space_ = Space::image(shape);
  image_.resize(static_cast<size_t>(from_.values()));
  pixels_.resize(image_.size());
  resized_.resize(static_cast<size_t>(space_.flat_dim()));
}

void ResizeObservation::resize(std::span<float> obs) {
  std::transform(image_.begin(), image_.end(), pixels_.begin(), opencv_pixel);
  resize_(pixels_, resized_);
  std::copy(resized_.begin(), resized_.end(), obs.begin());
}

void ResizeObservation::reset(std::optional<uint64_t> seed, std::span<float> obs) {
  inner_->reset(seed, image_);
  resize(obs);
}

StepResult ResizeObservation::step(std::span<const float> action, std::span<float> obs) {
  const StepResult result = inner_->step(action, image_);
  resize(obs);
  return result;
}

bool ResizeObservation::render_observation(std::span<const float> obs, Frame& frame) const {
  if (from_.channels != 1 && from_.channels != 3) return false;
  draw_pixels(obs, height_, width_, from_.channels, frame);
  return true;
}

}  // namespace rlrun
