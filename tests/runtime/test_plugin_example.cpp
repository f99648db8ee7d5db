// examples/custom_env as its README tells a user: copy the directory, configure and build it
// against this build tree's CMake package, `rlrun check-env` it, train on it with the
// `plugins:` line of its experiment file and with --plugin, and evaluate the model file.
#include <unistd.h>

#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>

#include "rlrun/core/zip_archive.hpp"
#include "runtime/cli_runner.hpp"
#include "test_paths.hpp"

using namespace rlrun;
using namespace rlrun::testing;
namespace fs = std::filesystem;

namespace {

const std::string kSource = RLRUN_SOURCE_DIR;

// The CMake package lives in the build directory, next to the binary.
std::string build_dir() { return fs::path(RLRUN_BINARY).parent_path().string(); }

}  // namespace

TEST_CASE("plugin example: builds out of tree, passes check-env, trains and evaluates",
          "[plugin][cli]") {
  // Per process: test binaries of other build directories may run this test at the same time.
  TempDir dir("plugin_example_" + std::to_string(getpid()));
  const std::string example = dir / "custom_env";
  fs::copy(kSource + "/examples/custom_env", example, fs::copy_options::recursive);
  fs::remove_all(example + "/build");  // a user's own earlier build, if any

  const auto configure =
      run_command("cmake -S " + example + " -B " + example + "/build -Drlrun_DIR=" + build_dir());
  INFO(configure.output);
  REQUIRE(configure.exit_code == 0);
  const auto build = run_command("cmake --build " + example + "/build");
  INFO(build.output);
  REQUIRE(build.exit_code == 0);
  CHECK(build.output.find("warning") == std::string::npos);
  const std::string library = example + "/build/libgo_left.so";
  REQUIRE(fs::exists(library));

  // Step 2 of the README.
  const auto check = run_rlrun("check-env GoLeft-v0 --plugin " + library);
  INFO(check.output);
  CHECK(check.exit_code == 0);
  CHECK(check.output.find("check_env: passed") != std::string::npos);
  CHECK(check.output.find("Discrete(2)") != std::string::npos);
  CHECK(check.output.find("100 steps (TimeLimit)") != std::string::npos);
  CHECK(run_rlrun("check-env GoLeft-v0 --plugin " + library + " --set grid_size=1").exit_code == 2);
  CHECK(run_rlrun("list GoLeft-v0 --plugin " + library).output.find("grid_size") !=
        std::string::npos);
  const auto unknown = run_rlrun("check-env GoLeft-v0");
  CHECK(unknown.exit_code == 2);

  // Step 3: the experiment file loads the plugin itself (path relative to the file).
  const auto train =
      run_rlrun("train " + example + "/go_left_a2c.yaml --set run.out_dir=" + dir / "runs");
  INFO(train.output);
  REQUIRE(train.exit_code == 0);
  const std::string run_dir = dir / "runs/go_left_a2c/seed1";
  CHECK(read_text(run_dir + "/config.yaml").find(library) != std::string::npos);

  // Step 4: the model file names the plugin, but a model file is data: rlrun loads no library
  // it names and says which one to pass; with --plugin the policy walks straight left.
  const auto refused_plugin = run_rlrun("eval --model " + run_dir + "/model.zip --episodes 10");
  CHECK(refused_plugin.exit_code == 2);
  CHECK(refused_plugin.output.find("pass --plugin " + library) != std::string::npos);
  const auto eval =
      run_rlrun("eval --model " + run_dir + "/model.zip --episodes 10 --plugin " + library);
  INFO(eval.output);
  REQUIRE(eval.exit_code == 0);
  CHECK(eval.output.find("mean_reward = 1.00") != std::string::npos);
  CHECK(eval.output.find("mean_ep_length = 9.0") != std::string::npos);
  CHECK(eval.output.find("success_rate = 1.000") != std::string::npos);
  // Or --trust (issue 41): the model's own `plugins:` line is loaded, after saying so.
  CHECK(refused_plugin.output.find("Or pass --trust to accept everything") != std::string::npos);
  const auto trusted = run_rlrun("eval --model " + run_dir + "/model.zip --episodes 10 --trust");
  INFO(trusted.output);
  CHECK(trusted.exit_code == 0);
  CHECK(trusted.output.find("(--trust): plugins[0] = " + library +
                            ": a plugin library rlrun "
                            "loads") != std::string::npos);
  CHECK(trusted.output.find("mean_reward = 1.00") != std::string::npos);

  // --plugin instead of the `plugins:` line; a missing library is a clear usage error.
  {
    std::ofstream out(dir / "no_plugins_line.yaml");
    out << "run: {total_timesteps: 200, out_dir: " << dir / "runs"
        << "}\n"
        << "env: {id: GoLeft-v0}\nalgo: {id: PPO, n_steps: 64, batch_size: 64}\n";
  }
  CHECK(run_rlrun("train " + dir / "no_plugins_line.yaml --plugin " + library).exit_code == 0);
  // API v2: a plugin env saves its state, so a run resumes exactly: 256 steps, then resumed to
  // 512, ends with the weights of 512 steps at once (constant schedules: the total does not
  // change the updates).
  const std::string plugin = " --plugin " + library;
  REQUIRE(run_rlrun("train " + dir / "no_plugins_line.yaml" + plugin +
                    " --set run.total_timesteps=512 --set run.name=straight")
              .exit_code == 0);
  const auto checkpointed = run_rlrun("train " + dir / "no_plugins_line.yaml" + plugin +
                                      " --set run.total_timesteps=256 --set checkpoint.freq=256"
                                      " --set run.name=resumed");
  INFO(checkpointed.output);
  REQUIRE(checkpointed.exit_code == 0);
  CHECK(checkpointed.output.find("cannot save its state") == std::string::npos);
  const auto resumed =
      run_rlrun("train --resume " + dir / "runs/resumed/seed0" + plugin + " --timesteps 512");
  INFO(resumed.output);
  REQUIRE(resumed.exit_code == 0);
  const ZipMembers straight = read_zip(dir / "runs/straight/seed0/model.zip");
  const ZipMembers again = read_zip(dir / "runs/resumed/seed0/model.zip");
  int tensors = 0;
  for (const auto& [name, bytes] : straight)
    if (name.size() > 4 && name.substr(name.size() - 4) == ".npy") {
      ++tensors;
      INFO(name);
      CHECK(again.at(name) == bytes);
    }
  CHECK(tensors > 4);
  // ... and draws itself: `rlrun record` films it (render() through rlrun/frame.hpp).
  const auto video = run_rlrun("record --model " + dir / "runs/straight/seed0/model.zip" + plugin +
                               " --output " + dir / "go_left.mp4 --episodes 1");
  INFO(video.output);
  CHECK(video.exit_code == 0);
  CHECK(fs::file_size(dir / "go_left.mp4") > 1000);
  const auto missing =
      run_rlrun("train " + dir / "no_plugins_line.yaml --plugin " + dir / "nowhere/libgo_left.so");
  CHECK(missing.exit_code == 2);
  CHECK(missing.output.find("not found") != std::string::npos);
}
