#pragma once
// `video: {freq, n_episodes, deterministic, fps, width, height, overlay}` — every `freq` TOTAL
// env steps, records `n_episodes` evaluation episodes of the current policy to
//     <run_dir>/videos/step_<N>.mp4
// (N = total env steps so far), like SB3's VecVideoRecorder with an eval env, through the
// same recorder as `rlrun record`. The env is a separate copy with the training
// normalisation statistics copied and frozen (as EvalCallback does), seeded
// run.seed + n_envs + k for the k-th video. ffmpeg is looked up when training starts, so a
// missing ffmpeg is reported before any training time is spent.
#include <cstdint>

#include "rlrun/core/config_checks.hpp"
#include "rlrun/render/video_limits.hpp"
#include "rlrun/runtime/callback.hpp"

namespace rlrun {

// The largest video side and rate: render/video_limits.hpp says why.
inline constexpr int kMaxVideoSide = kMaxFrameSide;

// The `section:` of the experiment file: an mp4 of evaluation episodes every `freq` steps.
struct VideoConfig {
  int64_t freq = 0;            // total env steps between videos (0 = off)
  int n_episodes = 1;          // episodes per video
  bool deterministic = true;
  std::optional<double> fps;   // null = the env's render fps
  int width = 0, height = 0;   // 0 = the env's frame size
  bool overlay = true;         // env id, episode, step, return
  template <class V>
  void visit(V& v) {
    v("freq", freq, "record videos/step_<N>.mp4 every `freq` TOTAL env steps (0 = never; needs ffmpeg)",
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


class VideoCallback : public Callback {
 public:
  // Throws RuntimeFailure when ffmpeg is missing, UsageError when the env cannot render.
  explicit VideoCallback(TrainingContext& context);
  bool on_step(int64_t num_timesteps) override;
  void write_state(StateWriter& out) const override;
  void read_state(const StateReader& in) override;

  int videos() const { return videos_; }

 private:
  TrainingContext& context_;
  const VideoConfig& config_;
  EnvPtr env_;
  int64_t next_;
  int videos_ = 0;
};

}  // namespace rlrun
