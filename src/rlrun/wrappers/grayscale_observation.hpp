#pragma once
// GrayscaleObservation: an RGB image observation (height, width, 3), values 0-255, to gray
// (Gymnasium 1.0 gymnasium/wrappers/transform_observation.py GrayscaleObservation): each pixel
// becomes uint8(0.2125 r + 0.7154 g + 0.0721 b) — the luminance weights of skimage's rgb2gray,
// summed in double in that order and truncated toward zero, as numpy's
// np.sum(np.multiply(obs, weights), axis=-1).astype(np.uint8) does (so a white pixel may come
// out 254, exactly as in Gymnasium). With `weights: opencv` it is OpenCV's COLOR_RGB2GRAY instead
// (wrappers/opencv_image_ops.hpp), as Gymnasium 0.29's GrayScaleObservation — the class rl-zoo's
// files name — and SB3's WarpFrame compute it. The result is Box(0, 255, (height, width), uint8), or
// (height, width, 1) with keep_dim (what SB3's CnnPolicy needs to see a channel axis).
#include <string>

#include "rlrun/core/config_checks.hpp"
#include "rlrun/env/wrapper.hpp"

namespace rlrun {

class GrayscaleObservation : public Wrapper {
 public:
  // Observations only (rlrun export reads this wrapper's observations: env/wrapper.hpp).
  bool exports_action_unchanged() const override { return true; }
  struct Config {
    bool keep_dim = false;
    std::string weights = "gymnasium";  // gymnasium (1.0, float) | opencv (0.29, SB3 WarpFrame)
    template <class V>
    void visit(V& v) {
      v("keep_dim", keep_dim,
        "keep a channel axis of 1: (height, width, 1) instead of (height, width)");
      v("weights", weights,
        "gymnasium (Gymnasium 1.0's float weights) or opencv (cv2 RGB2GRAY: Gymnasium 0.29, SB3)",
        OneOf{{"gymnasium", "opencv"}});
    }
  };
  // Throws std::invalid_argument unless the observation is a Box of shape (height, width, 3)
  // with bounds 0 and 255 (Gymnasium's asserts), or for unknown weights.
  GrayscaleObservation(EnvPtr inner, const Config& config);
  explicit GrayscaleObservation(EnvPtr inner) : GrayscaleObservation(std::move(inner), Config()) {}

  const Space& observation_space() const override { return space_; }
  void reset(std::optional<uint64_t> seed, std::span<float> obs) override;
  StepResult step(std::span<const float> action, std::span<float> obs) override;
  // Draws the gray image itself (the inner env cannot be drawn from it).
  bool render_observation(std::span<const float> obs, Frame& frame) const override;

  // One pixel's gray value, exactly as Gymnasium 1.0 computes it.
  static float gray(float r, float g, float b);

 private:
  void convert(std::span<float> obs) const;

  Space space_;
  bool opencv_weights_ = false;
  int height_ = 0, width_ = 0;
  std::vector<float> rgb_;  // the inner observation
};

}  // namespace rlrun
