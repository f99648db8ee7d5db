#include "rlrun/runtime/run/recorder.hpp"

#include <cstdio>
#include <filesystem>
#include <memory>
#include <stdexcept>

#include "rlrun/core/errors.hpp"
#include "rlrun/core/plural.hpp"
#include "rlrun/env/space_text.hpp"
#include "rlrun/env/step_all_agents.hpp"
#include "rlrun/frame.hpp"
#include "rlrun/render/overlay.hpp"
#include "rlrun/render/video_limits.hpp"
#include "rlrun/render/video_writer.hpp"
#include "rlrun/runtime/io/observation_log.hpp"
#include "rlrun/wrappers/monitor.hpp"

namespace rlrun {

namespace {

std::string format(const char* pattern, double value) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, pattern, value);
  return buffer;
}

// Where frames go: the video, the PNG directory, or both.
class FrameOutput {
 public:
  FrameOutput(const Env& env, const RecordOptions& options, RecordResult& result)
      : options_(options), result_(result) {
    if (options.video_path.empty() && options.frames_dir.empty())
      throw UsageError("nothing to record to: give a video file or a frames directory");
    const RenderSpec spec = env.render_spec();
    if (spec.width <= 0 || spec.height <= 0) throw UsageError(env.id() + " cannot render frames");
    result.width = options.width > 0 ? options.width : spec.width;
    result.height = options.height > 0 ? options.height : spec.height;
    result.fps = options.fps.value_or(spec.fps);
    if (!(result.fps > 0 && result.fps <= kMaxVideoFps))
      throw UsageError("fps must be > 0 and <= " + std::to_string(static_cast<int>(kMaxVideoFps)));
    // Checked before a frame is allocated or ffmpeg started (render/video_limits.hpp).
    const std::string size_problem = options.video_path.empty()
                                         ? check_frame_size(result.width, result.height)
                                         : check_video_size(result.width, result.height);
    if (!size_problem.empty()) throw UsageError(size_problem);
    try {
      frame_ = std::make_unique<Frame>(result.width, result.height);
    } catch (const std::invalid_argument& e) {
      throw UsageError(e.what());
    }
    if (!options.frames_dir.empty()) {
      std::error_code ec;
      std::filesystem::create_directories(options.frames_dir, ec);
      if (ec) throw RuntimeFailure("cannot create " + options.frames_dir + ": " + ec.message());
    }
    if (!options.video_path.empty()) {
      VideoOptions video;
      video.fps = result.fps;
      video_ =
          std::make_unique<VideoWriter>(options.video_path, result.width, result.height, video);
    }
  }

  Frame& frame() { return *frame_; }

  void emit(const std::vector<std::string>& overlay) {
    if (options_.overlay) draw_text_overlay(*frame_, overlay);
    if (video_) video_->write(*frame_);
    if (!options_.frames_dir.empty()) {
      char name[32];
      std::snprintf(name, sizeof name, "frame_%06lld.png", static_cast<long long>(result_.frames));
      try {
        frame_->write_png((std::filesystem::path(options_.frames_dir) / name).string());
      } catch (const std::runtime_error& e) {
        throw RuntimeFailure(e.what());
      }
    }
    ++result_.frames;
  }

  void finish() {
    if (video_) video_->close();
  }

 private:
  const RecordOptions& options_;
  RecordResult& result_;
  std::unique_ptr<Frame> frame_;
  std::unique_ptr<VideoWriter> video_;  // destroyed without finish(): no partial file
};

}  // namespace

RecordResult record_episodes(Env& env, const PolicyFn& policy, const RecordOptions& options,
                             const std::function<void()>& start_episode) {
  if (options.episodes < 1) throw UsageError("episodes must be >= 1");
  RecordResult result;
  // Made after the first reset: an env may know its frame size only once it has a state to
  // draw (a Python env's render() before reset may return None).
  std::unique_ptr<FrameOutput> output;
  const int obs_dim = env.observation_space().flat_dim();
  // Several agents: one column each, all stepped together (env/step_all_agents.hpp).
  const size_t obs_size = static_cast<size_t>(obs_dim) * env.num_agents();
  Eigen::MatrixXf obs(obs_dim, env.num_agents());
  Eigen::MatrixXf action;
  std::vector<StepResult> agent_steps;
  // The same bookkeeping as evaluate_policy: returns and lengths from the Monitor when there
  // is one (the env's true reward), else from the rewards seen here.
  const int r_key = env.info().find("episode.r");
  const int l_key = env.info().find("episode.l");
  const int success_key = env.info().find("is_success");
  // The overlay's running return too: the Monitor's (inside reward-changing wrappers such as
  // TransformReward, as in rl-zoo), so that the video agrees with `rlrun eval`.
  const Monitor* monitor = nullptr;
  for (Env* e = &env; e && !monitor;) {
    monitor = dynamic_cast<const Monitor*>(e);
    auto* wrapper = dynamic_cast<Wrapper*>(e);
    e = wrapper ? &wrapper->inner() : nullptr;
  }
  const auto shown_return = [&](double seen) { return monitor ? monitor->episode_return() : seen; };
  const std::string title =
      env.id() + (options.policy_label.empty() ? "" : "  " + options.policy_label);
  auto overlay = [&](int episode, int64_t step, double episode_return) {
    return std::vector<std::string>{title,
                                    "episode " + std::to_string(episode + 1) + "/" +
                                        std::to_string(options.episodes) + "  step " +
                                        std::to_string(step),
                                    "return " + format("%.2f", episode_return)};
  };
  auto draw = [&]() {
    if (!env.render(output->frame())) throw UsageError(env.id() + " cannot render frames");
  };

  for (int episode = 0; episode < options.episodes && !result.interrupted; ++episode) {
    env.reset(episode == 0 ? options.seed : std::nullopt, {obs.data(), obs_size});
    if (start_episode) start_episode();
    if (!output) output = std::make_unique<FrameOutput>(env, options, result);
    double episode_return = 0;
    int64_t length = 0;
    draw();
    output->emit(overlay(episode, 0, 0.0));
    while (true) {
      if (options.keep_going && !options.keep_going()) {
        result.interrupted = true;
        break;
      }
      policy(obs, action);
      const StepResult step =
          step_all_agents(env, {action.data(), static_cast<size_t>(action.size())},
                          {obs.data(), obs_size}, agent_steps);
      episode_return += step.reward;
      ++length;
      draw();
      output->emit(overlay(episode, length, shown_return(episode_return)));
      if (step.terminated || step.truncated) {
        const Info& info = env.info();
        EvalResult& r = result.episodes;
        r.returns.push_back(info.has(r_key) ? info.get(r_key) : episode_return);
        r.lengths.push_back(info.has(l_key) ? static_cast<int64_t>(info.get(l_key)) : length);
        if (info.has(success_key)) r.successes.push_back(info.get(success_key));
        break;
      }
    }
  }
  if (output) output->finish();
  return result;
}

RecordResult record_observations(const Env& env, const std::vector<std::string>& npy_files,
                                 const RecordOptions& options) {
  RecordResult result;
  FrameOutput output(env, options, result);
  const int obs_dim = env.observation_space().flat_dim();
  for (const std::string& file : npy_files) {
    const ObservationChunk chunk = read_observation_chunk(file);
    if (chunk.obs_dim != obs_dim)
      throw UsageError(file + ": rows have " + count_of(chunk.obs_dim, "value") + " but " +
                       env.id() + " observations are " + flat_layout(env.observation_space()) +
                       " (is this log from another env?)");
    const std::string name = std::filesystem::path(file).filename().string();
    for (int64_t row = 0; row < chunk.rows && !result.interrupted; ++row) {
      if (options.keep_going && !options.keep_going()) {
        result.interrupted = true;
        break;
      }
      const std::span<const float> obs(chunk.values.data() + row * obs_dim,
                                       static_cast<size_t>(obs_dim));
      bool drawn = false;
      try {
        drawn = env.render_observation(obs, output.frame());
      } catch (const std::invalid_argument& e) {
        throw UsageError(file + " row " + std::to_string(row) + ": " + e.what());
      }
      if (!drawn)
        throw UsageError(env.id() +
                         " cannot draw a frame from an observation (--from-obs needs "
                         "an env whose observation determines the picture)");
      output.emit({env.id() + "  observation log", name + "  row " + std::to_string(row),
                   "frame " + std::to_string(result.frames)});
    }
    if (result.interrupted) break;
  }
  output.finish();
  return result;
}

}  // namespace rlrun
