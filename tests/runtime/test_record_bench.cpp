// Recording speed (issue 5: 1000 CartPole frames at 600x400 in under 2 s). Measured, not
// asserted (docs/benchmarks.md): run `build/tests/rlrun_tests "[record_bench]"`.
#include <sys/resource.h>

#include <catch2/catch.hpp>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "rlrun/envs/classic/cartpole.hpp"
#include "rlrun/frame.hpp"
#include "rlrun/render/overlay.hpp"
#include "rlrun/render/video_writer.hpp"
#include "runtime/cli_runner.hpp"

namespace {

using Clock = std::chrono::steady_clock;

// Steps CartPole with a balancing rule (push the way the pole leans) so episodes are long,
// and hands every frame (after reset and after each step) with its overlay to `sink`.
template <class Sink>
void cartpole_frames(int n, rlrun::Frame& frame, Sink&& sink) {
  rlrun::CartPole env;
  std::vector<float> obs(4);
  env.reset(1, obs);
  int step = 0;
  for (int i = 0; i < n; ++i) {
    if (i > 0) {
      const float action[] = {obs[2] + 0.5f * obs[3] > 0 ? 1.0f : 0.0f};
      if (env.step(action, obs).terminated || ++step >= 500) {
        env.reset(std::nullopt, obs);
        step = 0;
      }
    }
    env.render(frame);
    rlrun::draw_text_overlay(frame,
                             {"CartPole-v1  bench", "episode 1/1  step " + std::to_string(step),
                              "return " + std::to_string(step)});
    sink(frame);
  }
}

// CPU seconds of this process and of its finished children (ffmpeg), for a loaded machine
// where wall time says little.
double cpu_seconds(int who) {
  rusage u{};
  getrusage(who, &u);
  return u.ru_utime.tv_sec + u.ru_stime.tv_sec + 1e-6 * (u.ru_utime.tv_usec + u.ru_stime.tv_usec);
}

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

}  // namespace

TEST_CASE("bench: record 1000 CartPole frames at 600x400", "[.bench][record_bench]") {
  constexpr int kFrames = 1000;
  rlrun::testing::TempDir dir("record_bench");
  rlrun::Frame frame(600, 400);

  auto start = Clock::now();
  cartpole_frames(kFrames, frame, [](const rlrun::Frame&) {});
  const double draw_only = seconds_since(start);

  start = Clock::now();
  const double self_cpu = cpu_seconds(RUSAGE_SELF), child_cpu = cpu_seconds(RUSAGE_CHILDREN);
  rlrun::VideoWriter video(dir / "bench.mp4", 600, 400, {.fps = 50});
  cartpole_frames(kFrames, frame, [&](const rlrun::Frame& f) { video.write(f); });
  video.close();
  const double total = seconds_since(start);
  const double rlrun_cpu = cpu_seconds(RUSAGE_SELF) - self_cpu;
  const double ffmpeg_cpu = cpu_seconds(RUSAGE_CHILDREN) - child_cpu;

  std::printf(
      "record bench: %d CartPole frames 600x400 (draw + overlay + H.264 %s): %.2f s "
      "(%.0f frames/s); CPU: rlrun %.2f s, ffmpeg %.2f s; drawing alone %.3f s; %.0f kB\n",
      kFrames, rlrun::VideoOptions{}.preset.c_str(), total, kFrames / total, rlrun_cpu, ffmpeg_cpu,
      draw_only, std::filesystem::file_size(dir / "bench.mp4") / 1024.0);
  CHECK(video.frames_written() == kFrames);
}
