#pragma once
// The `video:` section of an experiment file, as plain data (run/video_callback.hpp records
// the videos).
#include <cstdint>
#include <optional>

#include "rlrun/core/config_checks.hpp"
#include "rlrun/render/video_limits.hpp"

namespace rlrun {

// The largest video side and rate: render/video_limits.hpp says why.
inline constexpr int kMaxVideoSide = kMaxFrameSide;

// The `section:` of the experiment file: an mp4 of evaluation episodes every `freq` steps.
struct VideoConfig {
  int64_t freq = 0;    // total env steps between videos (0 = off)
  int n_episodes = 1;  // episodes per video
  bool deterministic = true;
  std::optional<double> fps;  // null = the env's render fps
  int width = 0, height = 0;  // 0 = the env's frame size
  bool overlay = true;        // env id, episode, step, return
  template <class V>
  void visit(V& v) {
    v("freq", freq,
      "record videos/step_<N>.mp4 every `freq` TOTAL env steps (0 = never; needs ffmpeg)",
      non_negative());
    v("n_episodes", n_episodes, "evaluation episodes per video", in_range(1, 10000));
    v("deterministic", deterministic, "use the deterministic policy");
    v("fps", fps, "frames per second (null = the env's, e.g. 50 for CartPole)",
      in_range(0, kMaxVideoFps).open_low());
    v("width", width, "frame width in pixels (0 = the env's, e.g. 600)",
      in_range(0, kMaxVideoSide));
    v("height", height, "frame height in pixels (0 = the env's, e.g. 400)",
      in_range(0, kMaxVideoSide));
    v("overlay", overlay, "draw env id, episode, step and return on the frames");
  }
};

}  // namespace rlrun
