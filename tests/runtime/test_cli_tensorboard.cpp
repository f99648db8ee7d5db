// TensorBoard event files and task metrics through the real binary, read back independently:
// tests/tensorboard/tfevents.py checks the TFRecord framing and CRCs with its own CRC-32C and
// decodes the Event / Summary / HParams messages it declares itself with Debian's
// python3-protobuf, against the run's progress.csv (tags, steps, values), also after a kill and
// a resume (no step twice, none missing).
#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>

#include "runtime/cli_runner.hpp"
#include "test_paths.hpp"

using namespace rlrun::testing;
namespace fs = std::filesystem;

namespace {

// tfevents.py check TB_RUN PROGRESS [--finished]; its JSON line or its reason.
CommandResult check_events(const std::string& tb_run, const std::string& progress,
                           bool finished = true) {
  return run_command(std::string("/usr/bin/python3 ") + RLRUN_SOURCE_DIR +
                     "/tests/tensorboard/tfevents.py check " + tb_run + " " + progress +
                     (finished ? " --finished" : ""));
}

std::vector<std::string> entries(const std::string& dir) {
  std::vector<std::string> names;
  std::error_code ec;
  for (const auto& e : fs::directory_iterator(dir, ec))
    names.push_back(e.path().filename().string());
  std::sort(names.begin(), names.end());
  return names;
}

std::string first_line(const std::string& path) {
  std::ifstream in(path);
  std::string line;
  std::getline(in, line);
  return line;
}

}  // namespace

TEST_CASE("tensorboard: a PPO run's event file matches progress.csv, eval and hparams included",
          "[cli][tensorboard]") {
  TempDir dir("tb_ppo");
  const std::string config = std::string(RLRUN_SOURCE_DIR) + "/configs/cartpole_ppo.yaml";
  const auto r =
      run_rlrun("--threads 1 train " + config + " --timesteps 12000 --out " + dir / "runs" +
                " --set eval.freq=4000 --set eval.n_episodes=3 --tensorboard-log " + dir / "tb" +
                " --set run.tensorboard_images=true");
  INFO(r.output);
  REQUIRE(r.exit_code == 0);
  CHECK(r.output.find("TensorBoard: " + dir / "tb/cartpole_ppo_1") != std::string::npos);
  REQUIRE(entries(dir / "tb") == std::vector<std::string>{"cartpole_ppo_1"});
  const auto files = entries(dir / "tb/cartpole_ppo_1");
  REQUIRE(files.size() == 1);
  CHECK(files[0].rfind("events.out.tfevents.", 0) == 0);
  const auto checked =
      check_events(dir / "tb/cartpole_ppo_1", dir / "runs/cartpole_ppo/seed1/progress.csv");
  INFO(checked.output);
  REQUIRE(checked.exit_code == 0);
  CHECK(checked.output.find("\"algo\": \"PPO\"") != std::string::npos);
  CHECK(checked.output.find("final/ep_rew_mean") != std::string::npos);
  CHECK(checked.output.find("final/eval_mean_reward") != std::string::npos);
  CHECK(checked.output.find("\"images\": [\"images/learning_curve\"]") != std::string::npos);
  CHECK(first_line(dir / "runs/cartpole_ppo/seed1/progress.csv").find("eval/mean_reward") !=
        std::string::npos);

  // The next run of the same name is _2 (SB3's numbering), in the same log directory.
  const auto again = run_rlrun("--threads 1 train " + config + " --timesteps 2048 --out " +
                               dir / "runs" + " --set run.tensorboard_log=" + dir / "tb");
  REQUIRE(again.exit_code == 0);
  CHECK(entries(dir / "tb") == std::vector<std::string>{"cartpole_ppo_1", "cartpole_ppo_2"});
}

TEST_CASE("tensorboard: a killed and resumed run continues its TensorBoard run, no step twice",
          "[cli][tensorboard][resume]") {
  TempDir dir("tb_resume_cli");
  const std::string config = std::string(RLRUN_SOURCE_DIR) + "/configs/cartpole_ppo.yaml";
  const std::string settings =
      " --set run.total_timesteps=200000 --set checkpoint.freq=8192"
      " --set checkpoint.keep=0 --set eval.freq=10000"
      " --set eval.n_episodes=3 --out " +
      dir / "runs" + " --tensorboard-log " + dir / "tb";
  const std::string run_dir = dir / "runs/cartpole_ppo/seed1";
  // Killed (SIGKILL) once the second checkpoint exists and the evaluation at 20 000 steps, after
  // it, is in evaluations.csv: rows after the checkpoint are in the files already. (Waiting for
  // that row, not for a fixed time: a fast CPU trains the whole run in a fraction of a second.)
  const std::string cmd =
      std::string(RLRUN_BINARY) + " --threads 1 train " + config + settings + " > " +
      dir / "cut.log" + " 2>&1 & pid=$!; while ! { [ -e " + run_dir +
      "/checkpoints/step_16384.zip ] && grep -q '^20000,' " + run_dir +
      "/evaluations.csv 2>/dev/null; } && kill -0 $pid 2>/dev/null; do sleep 0.001; done; "
      "kill -KILL $pid; wait $pid; echo exit=$?";
  const auto killed = run_command(cmd);
  INFO(killed.output << read_text(dir / "cut.log"));
  REQUIRE(killed.output.find("exit=137") != std::string::npos);

  // The run directory is untrusted: its TensorBoard directory needs the user's word.
  const auto refused = run_rlrun("--threads 1 train --resume " + run_dir);
  CHECK(refused.exit_code != 0);
  CHECK(refused.output.find("--set run.tensorboard_log=" + dir / "tb") != std::string::npos);

  const auto resumed =
      run_rlrun("--threads 1 train --resume " + run_dir + " --tensorboard-log " + dir / "tb");
  INFO(resumed.output);
  REQUIRE(resumed.exit_code == 0);
  CHECK(entries(dir / "tb") == std::vector<std::string>{"cartpole_ppo_1"});
  CHECK(entries(dir / "tb/cartpole_ppo_1").size() == 1);
  const auto checked = check_events(dir / "tb/cartpole_ppo_1", run_dir + "/progress.csv");
  INFO(checked.output);
  REQUIRE(checked.exit_code == 0);
  CHECK(checked.output.find("\"last_step\": 200192") != std::string::npos);
}

TEST_CASE("tensorboard: a sweep's runs share one log directory, named by run id",
          "[cli][tensorboard][sweep]") {
  TempDir dir("tb_sweep");
  std::ofstream(dir / "sweep.yaml")
      << "base: " << RLRUN_SOURCE_DIR << "/configs/cartpole_ppo.yaml\nout_dir: " << dir / "out"
      << "\nseeds: [1, 2]\ngrid: {algo.n_epochs: [2]}\n"
      << "set: {run.total_timesteps: 2048}\n";
  const auto expanded = run_rlrun("sweep " + dir / "sweep.yaml");
  INFO(expanded.output);
  REQUIRE(expanded.exit_code == 0);
  const auto ran = run_rlrun("--threads 1 sweep run " + dir / "out/manifest.yaml");
  INFO(ran.output);
  REQUIRE(ran.exit_code == 0);
  CHECK(entries(dir / "out/tensorboard") ==
        std::vector<std::string>{"n_epochs=2_seed1_1", "n_epochs=2_seed2_1"});
  const auto checked = check_events(dir / "out/tensorboard/n_epochs=2_seed2_1",
                                    dir / "out/runs/n_epochs=2/seed2/progress.csv");
  INFO(checked.output);
  CHECK(checked.exit_code == 0);
}

TEST_CASE("task metrics: a traffic DQN run logs waiting time in monitor.csv and progress.csv",
          "[cli][metrics][traffic]") {
  TempDir dir("metrics_traffic");
  const auto r = run_rlrun("--threads 1 train " + std::string(RLRUN_SOURCE_DIR) +
                           "/configs/traffic_dqn.yaml --timesteps 2880 --out " + dir / "runs");
  INFO(r.output);
  REQUIRE(r.exit_code == 0);
  const std::string run = dir / "runs/traffic_dqn/seed1";
  const std::string monitor = read_text(run + "/0.monitor.csv");
  CHECK(monitor.find("r,l,t,avg_waiting_time,avg_travel_time,throughput,total_queue_length\n") !=
        std::string::npos);
  const std::string header = first_line(run + "/progress.csv");
  for (const char* key : {"rollout/avg_waiting_time", "rollout/avg_travel_time",
                          "rollout/throughput", "rollout/total_queue_length"}) {
    INFO(key << " in " << header);
    CHECK(header.find(key) != std::string::npos);
  }
}

TEST_CASE("task metrics: grasp SAC logs rollout/success_rate and rollout/lift, info_keywords",
          "[cli][metrics]") {
  TempDir dir("metrics_grasp");
  const auto r = run_rlrun("--threads 1 train " + std::string(RLRUN_SOURCE_DIR) +
                           "/configs/grasp_sac.yaml --timesteps 400 --set algo.learning_starts=100"
                           " --set run.log_interval=1 --set eval.freq=400 --set eval.n_episodes=2"
                           " --out " +
                           dir / "runs");
  INFO(r.output);
  REQUIRE(r.exit_code == 0);
  const std::string run = dir / "runs/grasp_sac/seed1";
  const std::string header = first_line(run + "/progress.csv");
  CHECK(header.find("rollout/success_rate") != std::string::npos);
  CHECK(header.find("rollout/lift") != std::string::npos);
  CHECK(header.find("eval/lift") != std::string::npos);
  CHECK(read_text(run + "/0.monitor.csv").find("r,l,t,is_success,lift\n") != std::string::npos);
  CHECK(first_line(run + "/evaluations.csv") ==
        "timesteps,mean_reward,std_reward,mean_ep_length,success_rate,lift");

  // env.info_keywords chooses the columns: [] none, [distance] that one (any info key).
  const std::string grasp2d = std::string(RLRUN_SOURCE_DIR) + "/configs/grasp2d_dqn.yaml";
  const auto none = run_rlrun("--threads 1 train " + grasp2d + " --timesteps 500 --out " +
                              dir / "none" + " --set 'env.info_keywords=[]'");
  REQUIRE(none.exit_code == 0);
  CHECK(read_text(dir / "none/grasp2d_dqn/seed1/0.monitor.csv").find("\nr,l,t\n") !=
        std::string::npos);
  const auto distance =
      run_rlrun("--threads 1 train " + grasp2d + " --timesteps 2000 --out " + dir / "distance" +
                " --set 'env.info_keywords=[distance]'" + " --set run.log_interval=1");
  INFO(distance.output);
  REQUIRE(distance.exit_code == 0);
  CHECK(read_text(dir / "distance/grasp2d_dqn/seed1/0.monitor.csv").find("\nr,l,t,distance\n") !=
        std::string::npos);
  CHECK(first_line(dir / "distance/grasp2d_dqn/seed1/progress.csv").find("rollout/distance") !=
        std::string::npos);
}
