#pragma once
// Recording: runs episodes of a policy on one env and writes what the env draws, one frame
// after reset() and one after every step (Gymnasium's RecordVideo: an episode of L steps is
// L + 1 frames), to an mp4 (render/video_writer.hpp) and/or numbered PNGs, with an overlay
// of env id, episode, step and return so far. Used by `rlrun record`, `rlrun eval --record`
// and the training video callback. The episodes, seeds and returns are exactly those of
// evaluate_policy() (runtime/run/evaluator.hpp) for the same arguments.
#include <Eigen/Core>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "rlrun/env.hpp"
#include "rlrun/runtime/run/evaluator.hpp"

namespace rlrun {

struct RecordOptions {
  std::string video_path;  // mp4 to write; empty = none
  std::string frames_dir;  // PNGs frame_000000.png, ... ; empty = none
  int episodes = 1;
  std::optional<uint64_t> seed;  // seed of the first reset (later ones continue its stream)
  std::optional<double> fps;     // default: the env's render fps (Gymnasium's metadata)
  int width = 0, height = 0;     // 0 = the env's own frame size
  bool overlay = true;           // env id, episode, step, return
  std::string policy_label;      // shown in the overlay, e.g. "PPO deterministic"
  // Called before every step; false stops early (Ctrl-C). The video keeps what was recorded.
  std::function<bool()> keep_going;
};

struct RecordResult {
  EvalResult episodes;  // finished episodes only
  int64_t frames = 0;   // frames written (video and PNGs alike)
  int width = 0, height = 0;
  double fps = 0;
  bool interrupted = false;
};

// obs (obs_dim x 1) -> action (act_dim x 1), ready for env.step().
using PolicyFn = std::function<void(const Eigen::MatrixXf& obs, Eigen::MatrixXf& action)>;

// Throws UsageError when the env cannot render or the size is invalid, RuntimeFailure when
// ffmpeg is missing or fails (no video file is left behind then).
// `start_episode` (may be empty) is called after each reset, before the episode's first action
// (a recurrent model zeroes its state there; model_action_fn gives it).
RecordResult record_episodes(Env& env, const PolicyFn& policy, const RecordOptions& options,
                             const std::function<void()>& start_episode = {});

// Frames drawn from an observation log (runtime/io/observation_log.hpp: .npy chunks of shape
// (steps, obs_dim)), one per row, with env.render_observation(); the overlay names the file
// and row. Throws UsageError when the env cannot draw observations or a chunk does not fit.
RecordResult record_observations(const Env& env, const std::vector<std::string>& npy_files,
                                 const RecordOptions& options);

}  // namespace rlrun
