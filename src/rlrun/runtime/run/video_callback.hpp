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

#include "rlrun/runtime/experiment/video_config.hpp"
#include "rlrun/runtime/run/callback.hpp"

namespace rlrun {

class VideoCallback : public Callback {
 public:
  // Throws RuntimeFailure when ffmpeg is missing, UsageError when the env cannot render.
  VideoCallback(TrainingContext& context, const VideoConfig& config);
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
