#include "rlrun/runtime/run/video_callback.hpp"

#include <cstdio>

#include "rlrun/core/dir_handle.hpp"
#include "rlrun/core/errors.hpp"
#include "rlrun/core/interrupt.hpp"
#include "rlrun/core/plural.hpp"
#include "rlrun/render/video_writer.hpp"
#include "rlrun/runtime/experiment/env_factory.hpp"
#include "rlrun/runtime/experiment/env_statistics.hpp"
#include "rlrun/runtime/io/log_sinks.hpp"
#include "rlrun/runtime/run/evaluator.hpp"
#include "rlrun/runtime/run/recorder.hpp"

namespace rlrun {

VideoCallback::VideoCallback(TrainingContext& context, const VideoConfig& config)
    : context_(context),
      config_(config),
      env_(make_env(context.env_spec, context.registry, "", unix_time_now())),
      next_(config.freq) {
  VideoWriter::find_ffmpeg();  // fail now, not after the first `freq` steps
  if (env_->render_spec().width <= 0)
    throw UsageError("video.freq > 0 but " + context.env_spec.id + " cannot render frames");
  set_statistics_training(*env_, false);
  // videos/ inside the run directory, not a link to elsewhere (core/dir_handle.hpp); ffmpeg
  // then writes there by path (a race with someone replacing it meanwhile is not defended).
  DirHandle::open(context.run_dir).make_subdir("videos");
}

bool VideoCallback::on_step(int64_t num_timesteps) {
  if (!crossed(num_timesteps, config_.freq, next_)) return true;
  TensorMap statistics;
  save_model_statistics(context_.env.env(0), statistics);
  load_model_statistics(*env_, statistics, /*training=*/false);

  RecordOptions options;
  options.video_path = context_.run_dir + "/videos/step_" + std::to_string(num_timesteps) + ".mp4";
  options.episodes = config_.n_episodes;
  options.seed = context_.seed + static_cast<uint64_t>(context_.env_spec.section.n_envs) +
                 static_cast<uint64_t>(videos_++);
  options.fps = config_.fps;
  options.width = config_.width;
  options.height = config_.height;
  options.overlay = config_.overlay;
  options.policy_label = context_.algorithm.id() + " at step " + std::to_string(num_timesteps);
  options.keep_going = [] { return !interrupt_requested(); };
  const bool deterministic = config_.deterministic;
  Algorithm& algorithm = context_.algorithm;
  std::function<void()> start_episode;
  const PolicyFn act = model_action_fn(algorithm, *env_, deterministic, &start_episode);
  const RecordResult r = record_episodes(*env_, act, options, start_episode);
  if (context_.message)
    context_.message("video at " + count_of(num_timesteps, "step") + ": " + options.video_path +
                     " (" + count_of(r.frames, "frame") + ", return " +
                     format_log_value(r.episodes.mean_return()) + ")");
  return true;
}

void VideoCallback::write_state(StateWriter& out) const {
  out.put_int("next", next_);
  out.put_int("videos", videos_);
}

void VideoCallback::read_state(const StateReader& in) {
  next_ = in.get_count("next");  // crossed() counts up from it
  videos_ = static_cast<int>(in.get_count("videos", INT_MAX));
}

}  // namespace rlrun
