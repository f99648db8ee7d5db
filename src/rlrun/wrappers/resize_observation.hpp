#pragma once
// ResizeObservation: an image observation (height, width) or (height, width, channels), values
// 0-255, resized to `shape` [height, width] as Gymnasium's ResizeObservation does —
// cv2.resize(obs, (width, height), interpolation=cv2.INTER_AREA), bit for bit
// (wrappers/opencv_image_ops.hpp) — keeping the channel axis: Box(0, 255, shape + channels, uint8).
// `shape` is [height, width] (Gymnasium 1.0) or one number for a square (Gymnasium 0.29, which
// rl-zoo's CarRacing entry uses: `shape: 64`). Only shrinking is implemented (OpenCV's area
// path); a growing side is refused when the wrapper is built.
#include <string>
#include <vector>

#include "rlrun/core/config_fields.hpp"
#include "rlrun/env/wrapper.hpp"
#include "rlrun/wrappers/opencv_image_ops.hpp"

namespace rlrun {

// A size written in YAML as [height, width] or one number for both.
struct ResizeShape {
  int height = 84, width = 84;
};
void decode(const ConfigNode& n, ResizeShape& out);
YAML::Node encode(const ResizeShape& shape);

class ResizeObservation : public Wrapper {
 public:
  // Observations only (rlrun export reads this wrapper's observations: env/wrapper.hpp).
  bool exports_action_unchanged() const override { return true; }
  struct Config {
    ResizeShape shape;
    template <class V>
    void visit(V& v) {
      v("shape", shape, "the new [height, width], or one number for a square (default 84)");
    }
  };
  // Throws std::invalid_argument unless the observation is a Box of 2 or 3 dimensions with
  // bounds 0 and 255, or when OpenCV's area path cannot produce `shape` (a side grows).
  ResizeObservation(EnvPtr inner, const Config& config);
  explicit ResizeObservation(EnvPtr inner) : ResizeObservation(std::move(inner), Config()) {}

  const Space& observation_space() const override { return space_; }
  void reset(std::optional<uint64_t> seed, std::span<float> obs) override;
  StepResult step(std::span<const float> action, std::span<float> obs) override;
  // Draws the resized image itself (gray or RGB).
  bool render_observation(std::span<const float> obs, Frame& frame) const override;

 private:
  void resize(std::span<float> obs);

  Space space_;
  ImageSize from_;
  int height_ = 0, width_ = 0;
  OpencvAreaResize resize_;
  std::vector<float> image_;     // the inner observation
  std::vector<uint8_t> pixels_;  // as OpenCV reads it
  std::vector<uint8_t> resized_;
};

}  // namespace rlrun
