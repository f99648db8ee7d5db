// TensorBoardLog without the binary: run numbering, SB3's exclusions, resume from a checkpoint's
// state (the file cut back to its mark) and refusal of crafted state.
#include <catch2/catch.hpp>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>

#include "rlrun/core/errors.hpp"
#include "rlrun/runtime/io/tensorboard/tensorboard_log.hpp"
#include "runtime/cli_runner.hpp"

using namespace rlrun;
using namespace rlrun::testing;
namespace fs = std::filesystem;

namespace {

std::vector<std::string> entries(const std::string& dir) {
  std::vector<std::string> names;
  for (const auto& e : fs::directory_iterator(dir)) names.push_back(e.path().filename().string());
  std::sort(names.begin(), names.end());
  return names;
}

void no_note(const std::string&) {}

}  // namespace

TEST_CASE("tensorboard log: runs are numbered <name>_<N> as SB3 numbers them", "[tensorboard]") {
  TempDir dir("tb_numbering");
  const YAML::Node config = YAML::Load("run: {seed: 3}\nalgo: {id: PPO, learning_rate: 0.001}");
  { TensorBoardLog a = TensorBoardLog::start(dir.str(), "cartpole", config); }
  fs::create_directories(dir / "cartpole_7");
  fs::create_directories(dir / "cartpole_x");
  fs::create_directories(dir / "cartpole_ppo_9");  // another name
  TensorBoardLog b = TensorBoardLog::start(dir.str(), "cartpole", config);
  CHECK(b.run_dir() == dir / "cartpole_8");
  CHECK(entries(dir.str()) == std::vector<std::string>{"cartpole_1", "cartpole_7", "cartpole_8",
                                                       "cartpole_ppo_9", "cartpole_x"});
  // A name with a folder: DIR/group/name_N.
  TensorBoardLog c = TensorBoardLog::start(dir.str(), "group/run", config);
  CHECK(c.run_dir() == dir / "group/run_1");
  CHECK(entries(dir / "cartpole_8").size() == 1);
  CHECK(entries(dir / "cartpole_8").front().rfind("events.out.tfevents.", 0) == 0);
}

TEST_CASE("tensorboard log: SB3's tensorboard exclusions", "[tensorboard]") {
  for (const char* key : {"time/iterations", "time/time_elapsed", "time/total_timesteps",
                          "time/episodes", "train/n_updates"})
    CHECK(excluded_from_tensorboard(key));
  for (const char* key : {"time/fps", "rollout/ep_rew_mean", "train/loss", "eval/mean_reward"})
    CHECK_FALSE(excluded_from_tensorboard(key));
}

TEST_CASE("tensorboard log: resume cuts the event file back to the checkpoint", "[tensorboard]") {
  TempDir dir("tb_resume");
  TensorMap tensors;
  std::string file;
  uint64_t mark = 0;
  {
    TensorBoardLog log = TensorBoardLog::start(dir.str(), "run", YAML::Load("a: 1"));
    log.write({{"rollout/ep_rew_mean", 10.0}}, 100);
    log.write_state(StateWriter(tensors, "tb/"));
    file = entries(dir / "run_1").front();
    mark = fs::file_size(dir / ("run_1/" + file));
    log.write({{"rollout/ep_rew_mean", 20.0}}, 200);  // after the checkpoint: cut on resume
  }
  REQUIRE(fs::file_size(dir / ("run_1/" + file)) > mark);
  {
    TensorBoardLog log =
        TensorBoardLog::resume(dir.str(), "run", StateReader(tensors, "tb/"), no_note);
    CHECK(log.run_dir() == dir / "run_1");
    CHECK(fs::file_size(dir / ("run_1/" + file)) == mark);
    log.write({{"rollout/ep_rew_mean", 20.0}}, 200);
  }
  CHECK(entries(dir / "run_1") == std::vector<std::string>{file});

  SECTION("a crafted checkpoint cannot name another file") {
    const auto crafted = [&](const std::string& run, const std::string& name) {
      TensorMap t = tensors;
      StateWriter w(t, "tb/");
      w.put_string("run", run);
      w.put_string("file", name);
      return t;
    };
    for (const auto& [run, name] : std::vector<std::pair<std::string, std::string>>{
             {"../run_1", file},
             {"other_1", file},
             {"run_x", file},
             {"run_1", "../../x"},
             {"run_1", "model.zip"},
             {"run_1", "events.out.tfevents.1/../x"}}) {
      INFO(run << " " << name);
      const TensorMap t = crafted(run, name);
      CHECK_THROWS_AS(TensorBoardLog::resume(dir.str(), "run", StateReader(t, "tb/"), no_note),
                      StateMismatch);
    }
  }
  SECTION("an event file shorter than the mark is refused") {
    fs::resize_file(dir / ("run_1/" + file), mark / 2);
    CHECK_THROWS_AS(TensorBoardLog::resume(dir.str(), "run", StateReader(tensors, "tb/"), no_note),
                    RuntimeFailure);
  }
  SECTION("a deleted event file: a new one, with a note") {
    fs::remove(dir / ("run_1/" + file));
    std::string note;
    TensorBoardLog log = TensorBoardLog::resume(dir.str(), "run", StateReader(tensors, "tb/"),
                                                [&](const std::string& line) { note = line; });
    CHECK(note.find("is gone") != std::string::npos);
    CHECK(entries(dir / "run_1").size() == 1);
  }
}

// What one progress row costs in TensorBoard: encoding and writing an Event of the keys of a
// PPO CartPole row (14 scalars), through the sink as training calls it. Measured, not asserted
// (docs/benchmarks.md): `build/tests/rlrun_tests "[tensorboard_bench]"`, run by
// scripts/bench/tensorboard.sh.
TEST_CASE("bench: TensorBoard cost per progress row", "[.bench][tensorboard_bench]") {
  TempDir dir("tb_bench");
  TensorBoardLog log = TensorBoardLog::start(dir.str(), "bench", YAML::Load("a: 1"));
  LogRow row;
  for (const char* key :
       {"rollout/ep_len_mean", "rollout/ep_rew_mean", "time/fps", "time/iterations",
        "time/time_elapsed", "time/total_timesteps", "train/approx_kl", "train/clip_fraction",
        "train/clip_range", "train/entropy_loss", "train/explained_variance", "train/learning_rate",
        "train/loss", "train/n_updates", "train/policy_gradient_loss", "train/value_loss"})
    row[key] = 0.123456789;
  constexpr int kRows = 20000;
  const auto start = std::chrono::steady_clock::now();
  for (int i = 0; i < kRows; ++i) log.write(row, 256 * (i + 1));
  const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::printf("| TensorBoard event per progress row (16 keys, 14 written) | %.1f us |\n",
              s / kRows * 1e6);
}
