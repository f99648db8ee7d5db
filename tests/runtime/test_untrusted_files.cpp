// Model files, checkpoints and run directories are data from anyone (docs/security.md): the
// security review's crafted inputs, made here by the test, through the real binary. Each may
// make rlrun refuse; none may run code, write or delete outside the run, or resume twice.
#include <catch2/catch.hpp>
#include <csignal>
#include <filesystem>
#include <fstream>
#include <thread>

#include "rlrun/core/npy.hpp"
#include "rlrun/core/state_dict.hpp"
#include "rlrun/core/zip_archive.hpp"
#include "runtime/cli_runner.hpp"
#include "runtime/marker_library.hpp"
#include "runtime/peak_memory_bound.hpp"
#include "test_paths.hpp"

using namespace rlrun;
using namespace rlrun::testing;
namespace fs = std::filesystem;

namespace {

const std::string kConfigs = std::string(RLRUN_SOURCE_DIR) + "/configs";

void write_file(const std::string& path, const std::string& text) {
  std::ofstream out(path);
  out << text;
}

// Rewrites one member of a zip (a model file or checkpoint) as an attacker would.
void replace_member(const std::string& zip, const std::string& member, const std::string& text) {
  ZipMembers members = read_zip(zip);
  members[member] = std::vector<uint8_t>(text.begin(), text.end());
  write_zip_atomic(zip, members);
}

// Sets a string or int of a checkpoint's training state (`training/...` .npy members).
void replace_state(const std::string& zip, const std::string& key, const std::string* text,
                   const int64_t* number) {
  ZipMembers members = read_zip(zip);
  TensorMap tensors;
  StateWriter writer(tensors);
  if (text) writer.put_string(key, *text);
  if (number) writer.put_int(key, *number);
  members[key + ".npy"] = encode_npy(tensors.at(key));
  write_zip_atomic(zip, members);
}

// A CartPole PPO run with two checkpoints (steps 256 and 512) and a model.
std::string train_with_checkpoints(const TempDir& dir) {
  const auto r =
      run_rlrun("train " + kConfigs + "/cartpole_ppo.yaml --set run.total_timesteps=512" +
                " --set checkpoint.freq=256 --set run.out_dir=" + dir.str());
  INFO(r.output);
  REQUIRE(r.exit_code == 0);
  return dir / "cartpole_ppo/seed1";
}

}  // namespace

TEST_CASE("untrusted: a checkpoint's log-file names cannot reach outside the run",
          "[cli][security]") {
  TempDir dir("untrusted_marks");
  const std::string run = train_with_checkpoints(dir);
  const std::string victim = dir / "victim.txt";
  write_file(victim, "precious\nlines\n");
  const std::string checkpoint = run + "/checkpoints/step_256.zip";
  const std::string escape = "../../../victim.txt";
  fs::copy_file(checkpoint, dir / "original.zip");
  for (int64_t lines : {0, 1}) {  // 0 deleted the file, 1 rewrote it
    fs::copy_file(dir / "original.zip", dir / "copy.zip", fs::copy_options::overwrite_existing);
    replace_state(dir / "copy.zip", "training/files/0/name", &escape, nullptr);
    replace_state(dir / "copy.zip", "training/files/0/lines", nullptr, &lines);
    fs::copy_file(dir / "copy.zip", checkpoint, fs::copy_options::overwrite_existing);
    const auto r = run_rlrun("train --resume " + checkpoint);
    INFO(r.output);
    CHECK(r.exit_code == 1);
    CHECK(r.output.find("names a log file '../../../victim.txt'") != std::string::npos);
    CHECK(read_text(victim) == "precious\nlines\n");
  }
}

TEST_CASE("untrusted: a model file names no library, program or output file that runs",
          "[cli][security]") {
  TempDir dir("untrusted_model");
  const std::string marker = dir / "code_ran";
  // A library whose constructor runs on dlopen, and a script: either would leave the marker.
  build_marker_library(dir, marker);
  write_file(dir / "evil.sh", "#!/bin/sh\ntouch " + marker + "\n");
  fs::permissions(dir / "evil.sh", fs::perms::owner_all);
  const std::string victim = dir / "victim.txt";
  write_file(victim, "precious\n");

  const auto trained =
      run_rlrun("train " + kConfigs + "/cartpole_ppo.yaml --set run.total_timesteps=256" +
                " --set run.out_dir=" + dir.str());
  REQUIRE(trained.exit_code == 0);
  const std::string model = dir / "cartpole_ppo/seed1/model.zip";
  const std::string config = read_text(dir / "cartpole_ppo/seed1/config.yaml");

  // plugins: [libevil.so] is not loaded.
  replace_member(model, "config.yaml", "plugins: [" + dir / "libevil.so" + "]\n" + config);
  auto r = run_rlrun("eval --model " + model + " --episodes 1");
  INFO(r.output);
  CHECK(r.exit_code == 0);  // CartPole needs no plugin: the list is ignored
  CHECK_FALSE(fs::exists(marker));

  // A traffic env naming a script as its SUMO binary, an output file, a scenario elsewhere.
  const std::string traffic = "env: {id: TrafficSignal-v0, kwargs: {";
  const std::vector<std::pair<std::string, std::string>> cases{
      {"sumo_binary: " + dir / "evil.sh", "env.kwargs.sumo_binary: a program to run"},
      {"tripinfo_output: " + victim, "env.kwargs.tripinfo_output: an output file"},
      {"scenario: " + dir / "evil.sumocfg", "env.kwargs.scenario: a simulator input file"}};
  for (const auto& [kwarg, message] : cases) {
    replace_member(model, "config.yaml",
                   "run: {name: x}\n" + traffic + kwarg + "}}\nalgo: {id: DQN}\n");
    r = run_rlrun("eval --model " + model + " --episodes 1");
    INFO(r.output);
    CHECK(r.exit_code == 2);
    CHECK(r.output.find(message) != std::string::npos);
    CHECK(r.output.find("--set ") != std::string::npos);  // how to vouch for it
  }
  CHECK_FALSE(fs::exists(marker));
  CHECK(read_text(victim) == "precious\n");
}

TEST_CASE("untrusted: a resumed run's config.yaml loads no library", "[cli][security]") {
  TempDir dir("untrusted_run_dir");
  const std::string run = train_with_checkpoints(dir);
  const std::string marker = dir / "code_ran";
  build_marker_library(dir, marker);
  const std::string config = read_text(run + "/config.yaml");
  write_file(run + "/config.yaml", "plugins: [" + dir / "libevil.so" + "]\n" + config);
  const auto r = run_rlrun("train --resume " + run + "/checkpoints/step_256.zip");
  INFO(r.output);
  CHECK(r.exit_code == 0);
  CHECK_FALSE(fs::exists(marker));
}

TEST_CASE("untrusted: two resumes of one run at once: the second is refused", "[cli][security]") {
  TempDir dir("untrusted_lock");
  const std::string run = train_with_checkpoints(dir);
  // The first resume trains for long; the second starts while it holds the run.
  const std::string first_log = dir / "first.log";
  const std::string command = std::string(RLRUN_BINARY) + " train --resume " + run +
                              " --timesteps 100000000 > " + first_log + " 2>&1 & echo $!";
  const auto started = run_command(command);
  const pid_t first = std::stoi(started.output);
  for (int i = 0; i < 200 && read_text(first_log).find("resuming") == std::string::npos; ++i)
    std::this_thread::sleep_for(std::chrono::milliseconds(25));
  const auto second = run_rlrun("train --resume " + run + " --timesteps 100000000");
  kill(first, SIGKILL);
  INFO(second.output);
  CHECK(second.exit_code == 1);
  CHECK(second.output.find("another rlrun process (pid " + std::to_string(first) + ")") !=
        std::string::npos);
  // The kernel dropped the killed holder's lock: the run resumes again.
  for (int i = 0; i < 200 && fs::exists("/proc/" + std::to_string(first)); ++i)
    std::this_thread::sleep_for(std::chrono::milliseconds(25));
  const std::string third_log = dir / "third.log";
  const pid_t third = std::stoi(run_command(std::string(RLRUN_BINARY) + " train --resume " + run +
                                            " > " + third_log + " 2>&1 & echo $!")
                                    .output);
  for (int i = 0; i < 400 && read_text(third_log).find("resuming") == std::string::npos &&
                  read_text(third_log).find("error") == std::string::npos;
       ++i)
    std::this_thread::sleep_for(std::chrono::milliseconds(25));
  kill(third, SIGKILL);
  INFO(read_text(third_log));
  CHECK(read_text(third_log).find("resuming") != std::string::npos);
}

TEST_CASE(
    "untrusted: stale temporaries are removed, a damaged newest checkpoint is skipped, "
    "counters are checked",
    "[cli][security]") {
  TempDir dir("untrusted_resume");
  const std::string run = train_with_checkpoints(dir);
  write_file(run + "/checkpoints/step_768.zip.tmp.a1B2c3", "half a zip");
  write_file(run + "/config.yaml.tmp", "half a file");
  // The newest checkpoint is cut short (a copy that stopped, a full disk).
  const std::string newest = run + "/checkpoints/step_512.zip";
  const std::string whole = read_text(newest);
  write_file(newest, whole.substr(0, whole.size() / 2));
  auto r = run_rlrun("train --resume " + run + " --timesteps 768");
  INFO(r.output);
  CHECK(r.exit_code == 0);
  CHECK(r.output.find("note: skipping checkpoint " + newest) != std::string::npos);
  CHECK(r.output.find("resuming PPO on CartPole-v1 from " + run + "/checkpoints/step_256.zip") !=
        std::string::npos);
  CHECK_FALSE(fs::exists(run + "/checkpoints/step_768.zip.tmp.a1B2c3"));
  CHECK_FALSE(fs::exists(run + "/config.yaml.tmp"));

  // A checkpoint claiming 2^62 steps is refused, not "trained 4611686018427387904 steps".
  const std::string checkpoint = run + "/checkpoints/step_256.zip";
  ZipMembers members = read_zip(checkpoint);
  std::string text(members["meta.json"].begin(), members["meta.json"].end());
  text.replace(text.find("\"num_timesteps\": 256"), 20, "\"num_timesteps\": 4611686018427387904");
  replace_member(checkpoint, "meta.json", text);
  r = run_rlrun("train --resume " + checkpoint);
  INFO(r.output);
  CHECK(r.exit_code == 1);
  CHECK(r.output.find("step 4611686018427387904, outside the run's 0..768") != std::string::npos);
  CHECK(r.output.find("trained 4611686018427387904") == std::string::npos);
}

TEST_CASE("untrusted: rlrun report reads a run's config.yaml within the config bounds",
          "[cli][security]") {
  TempDir dir("untrusted_report");
  const std::string run = dir / "run";
  fs::create_directories(run);
  // An alias bomb (dump_yaml of it, as report groups runs by their config, would never end).
  const std::string bomb = yaml_alias_bomb();
  write_file(run + "/config.yaml", "run: {name: x, seed: 1}\n" + bomb);
  const auto r = run_command_measured("timeout 60 " + std::string(RLRUN_BINARY) + " report " + run);
  INFO(r.output);
  CHECK(r.exit_code == 1);
  CHECK(r.output.find(run + "/config.yaml") != std::string::npos);
  CHECK(r.peak_rss_kb < peak_rss_bound_kb(300 * 1024));
  // A stray flow character (yaml-cpp's endless document loop) and a bad seed: refused too.
  write_file(run + "/config.yaml", "run: {name: x, seed: [1]}\n");
  CHECK(run_rlrun("report " + run).exit_code == 1);
  write_file(run + "/config.yaml", "# broken\n, 300]\n");
  CHECK(run_rlrun("report " + run).exit_code == 1);
}
