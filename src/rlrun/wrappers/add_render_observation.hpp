#pragma once
// AddRenderObservation: the env's rendered picture as the observation (Gymnasium 1.0
// gymnasium/wrappers/rendering.py AddRenderObservation, formerly PixelObservationWrapper):
//   render_only: true    Box(0, 255, (height, width, 3), uint8), the RGB frame (channels-last, row 0
//                        at the top, as env.render() returns it)
//   render_only: false   Dict{obs_key: the env's observation, render_key: that frame}
// Gymnasium renders at the env's own size (CartPole 600x400); `width` / `height` (rlrun's
// addition, 0 = the env's size) draw the frame directly at another size, e.g. 84x84 for a CNN,
// with the scene letterboxed as `rlrun record` draws it. The frame is drawn after every reset
// and step, from the state the env is in then.
// The pixel Box is uint8 like Gymnasium's: SB3's is_image_space accepts it, a CNN policy divides
// it by 255, and replay buffers keep it as bytes.
#include <string>
#include <vector>

#include "rlrun/core/config_checks.hpp"
#include "rlrun/env/wrapper.hpp"
#include "rlrun/frame.hpp"

namespace rlrun {

class AddRenderObservation : public Wrapper {
 public:
  // Observations only (rlrun export reads this wrapper's observations: env/wrapper.hpp).
  bool exports_action_unchanged() const override { return true; }
  struct Config {
    bool render_only = true;
    std::string render_key = "pixels";
    std::string obs_key = "state";
    int width = 0, height = 0;
    template <class V>
    void visit(V& v) {
      v("render_only", render_only,
        "the frame alone (true) or a Dict of the env's observation and the frame (false)");
      v("render_key", render_key, "the frame's key when render_only is false");
      v("obs_key", obs_key, "the env's observation's key when render_only is false");
      v("width", width, "frame width in pixels (0: the env's own render size)", in_range(0, 4096));
      v("height", height, "frame height in pixels (0: the env's own render size)",
        in_range(0, 4096));
    }
  };
  // Throws std::invalid_argument for an env that cannot render, a Dict observation with
  // render_only false (one level of keys, as SB3), or equal keys.
  AddRenderObservation(EnvPtr inner, const Config& config);
  explicit AddRenderObservation(EnvPtr inner) : AddRenderObservation(std::move(inner), Config()) {}

  const Space& observation_space() const override { return space_; }
  void reset(std::optional<uint64_t> seed, std::span<float> obs) override;
  StepResult step(std::span<const float> action, std::span<float> obs) override;
  // Draws the observation's own frame, scaled to `frame` (nearest pixel).
  bool render_observation(std::span<const float> obs, Frame& frame) const override;

 private:
  // Draws the env's current state into frame_ and copies it into obs at pixels_at_.
  void observe(std::span<float> obs);

  Space space_;
  int pixels_at_ = 0;  // where the frame's floats start in an observation
  int state_at_ = 0;   // where the env's observation starts (render_only false)
  int state_dim_ = 0;  // 0 with render_only
  Frame frame_;
  std::vector<uint8_t> rgb_;  // the frame's bytes
  std::vector<float> state_;  // the env's observation when only the frame is kept
};

}  // namespace rlrun
