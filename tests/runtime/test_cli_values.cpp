// Numeric command-line values (issue 15, item 12), through the real binary: range errors say
// the rule in a line (not DBL_MAX in 309 digits), every command taking --seed refuses seeds
// outside 0 .. 2^63 - 1 instead of wrapping them, and record bounds frame sizes before it
// allocates anything or starts ffmpeg.
#include <catch2/catch.hpp>

#include <chrono>
#include <filesystem>
#include <string>
#include <vector>

#include "rlrun/render/video_limits.hpp"
#include "runtime/cli_runner.hpp"
#include "test_paths.hpp"

using namespace rlrun;
using namespace rlrun::testing;
namespace fs = std::filesystem;

namespace {

const std::string kConfigs = std::string(RLRUN_SOURCE_DIR) + "/configs/";

bool contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

// A refused value: exit 2, the option and its rule in a short message, nothing from CLI11's
// DBL_MAX bound.
void check_refused(const std::string& args, const std::string& says) {
  const auto r = run_rlrun(args);
  INFO(args << "\n" << r.output);
  CHECK(r.exit_code == 2);
  CHECK(contains(r.output, says));
  CHECK_FALSE(contains(r.output, "17976931348623157"));
  CHECK(r.output.size() < 400);
}

}  // namespace

TEST_CASE("CLI: out-of-range seeds are refused by every command taking --seed", "[cli][values]") {
  TempDir dir("cli_seed_values");
  const std::vector<std::string> commands = {
      "train " + kConfigs + "cartpole_ppo.yaml --out " + dir / "runs",
      "eval --env CartPole-v1 --policy random --episodes 1",
      "record --env CartPole-v1 --policy random --output " + dir / "v.mp4",
      "check-env CartPole-v1",
  };
  const std::string rule = "--seed: seeds are integers from 0 to 9223372036854775807 (2^63 - 1)";
  for (const std::string& command : commands)
    for (const char* seed : {"-1", "18446744073709551615", "18446744073709551616",
                             "9223372036854775808", "1e23", "1.5", "seven"})
      check_refused(command + " --seed " + seed, rule + ", got '" + seed + "'");
  CHECK(fs::is_empty(dir.str()));  // nothing trained, nothing recorded

  // The largest seed is a seed: the same episode every time.
  const auto top =
      run_rlrun("eval --env CartPole-v1 --policy random --episodes 1 --seed 9223372036854775807");
  INFO(top.output);
  CHECK(top.exit_code == 0);
  CHECK(run_rlrun("eval --env CartPole-v1 --policy random --episodes 1 --seed 9223372036854775807")
            .output == top.output);
}

TEST_CASE("CLI: counts and rates say their rule", "[cli][values]") {
  TempDir dir("cli_count_values");
  const std::string train = "train " + kConfigs + "cartpole_ppo.yaml --out " + dir / "runs";
  check_refused("eval --env CartPole-v1 --policy random --episodes 0",
                "--episodes: must be an integer >= 1, got '0'");
  check_refused("eval --env CartPole-v1 --policy random --episodes 2.5",
                "--episodes: must be an integer >= 1, got '2.5'");
  check_refused("eval --env CartPole-v1 --policy random --episodes 1e10",
                "--episodes: must be an integer >= 1, got '1e10'");
  check_refused("check-env CartPole-v1 --steps 0", "--steps: must be an integer >= 1, got '0'");
  check_refused("check-env CartPole-v1 --episodes -1",
                "--episodes: must be an integer >= 0, got '-1'");
  check_refused(train + " --timesteps 0", "--timesteps: must be an integer >= 1, got '0'");
  check_refused(train + " --timesteps 1e30", "--timesteps: must be an integer >= 1, got '1e30'");
  check_refused(train + " -j 0", "--jobs: must be an integer >= 1, got '0'");
  check_refused("sweep run " + dir / "m.yaml" + " --index -2",
                "--index: must be an integer >= 0, got '-2'");
  check_refused("--threads 0 list",
                "--threads must be a whole number from 1 to 4096 or auto (the CPUs this process "
                "may use), got '0'");
  check_refused("record --env CartPole-v1 --policy random --fps 0 --output " + dir / "v.mp4",
                "--fps: must be a number > 0 and <= 1000, got '0'");
  check_refused("record --env CartPole-v1 --policy random --fps inf --output " + dir / "v.mp4",
                "--fps: must be a number > 0 and <= 1000, got 'inf'");
  CHECK(fs::is_empty(dir.str()));

  // Integers as the config files write them still work.
  const auto r = run_rlrun(train + " --timesteps 1e3 --seed 3");
  INFO(r.output);
  CHECK(r.exit_code == 0);
  CHECK(contains(read_text(dir / "runs/cartpole_ppo/seed3/config.yaml"), "total_timesteps: 1000"));
}

TEST_CASE("record --size: bounded before anything is allocated or ffmpeg starts",
          "[cli][values][record]") {
  TempDir dir("cli_record_size");
  const std::string base = "record --env CartPole-v1 --policy random ";
  const auto start = std::chrono::steady_clock::now();
  check_refused(base + "--size 16384x16384 --output " + dir / "v.mp4",
                "--size 16384x16384: video size 16384x16384: width and height must be between 2 "
                "and 4096");
  check_refused(base + "--size 16384x16384 --frames " + dir / "frames",
                "--size 16384x16384: frame size 16384x16384: width and height must be between 1 "
                "and 4096");
  check_refused(base + "--size 601x400 --output " + dir / "v.mp4", "must be even");
  check_refused(base + "--size 0x400 --output " + dir / "v.mp4", "between 2 and 4096");
  CHECK(std::chrono::steady_clock::now() - start < std::chrono::seconds(5));
  CHECK(fs::is_empty(dir.str()));
  // Odd sizes are fine for PNG frames.
  const auto png = run_rlrun(base + "--size 33x21 --frames " + dir / "frames");
  INFO(png.output);
  CHECK(png.exit_code == 0);
}

TEST_CASE("check_video_size / check_frame_size: the one place of the frame-size rule",
          "[render][video]") {
  CHECK(check_video_size(600, 400).empty());
  CHECK(check_video_size(kMaxFrameSide, kMaxFrameSide).empty());
  CHECK(check_video_size(2, 2).empty());
  CHECK_FALSE(check_video_size(kMaxFrameSide + 2, 400).empty());
  CHECK_FALSE(check_video_size(600, 401).empty());
  CHECK_FALSE(check_video_size(0, 400).empty());
  CHECK_FALSE(check_video_size(-2, 400).empty());
  CHECK(check_frame_size(1, 1).empty());
  CHECK(check_frame_size(601, 401).empty());
  CHECK_FALSE(check_frame_size(kMaxFrameSide + 1, 1).empty());
  CHECK_FALSE(check_frame_size(0, 10).empty());
}
