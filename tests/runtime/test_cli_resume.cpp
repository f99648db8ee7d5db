// End-to-end tests of exact resume, run as a user would: `rlrun train` is interrupted with
// SIGINT (checkpoint at the next safe point) or killed with SIGKILL (the last periodic
// checkpoint, files already past it), `rlrun train --resume RUN_DIR` finishes it, and the run
// must end with the uninterrupted run's weights (bit for bit), progress.csv rows (time/ columns
// aside), monitor episodes and evaluations.csv. Also: divergence stops and --resume refusals.
#include <catch2/catch.hpp>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

#include "rlrun/core/zip_archive.hpp"
#include "rlrun/runtime/io/log_sinks.hpp"
#include "rlrun/runtime/io/session_summary.hpp"
#include "runtime/cli_runner.hpp"
#include "test_paths.hpp"

using namespace rlrun;
using namespace rlrun::testing;
namespace fs = std::filesystem;

namespace {

std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> lines;
  std::stringstream s(text);
  for (std::string line; std::getline(s, line);) lines.push_back(line);
  return lines;
}

std::vector<std::string> cells_of(const std::string& line) { return split_csv_line(line); }

// progress.csv as rows of key -> value, without the wall-clock columns (time/fps,
// time/time_elapsed differ between any two runs).
std::vector<std::map<std::string, std::string>> progress_rows(const std::string& path) {
  const std::vector<std::string> lines = lines_of(read_text(path));
  std::vector<std::map<std::string, std::string>> rows;
  if (lines.empty()) return rows;
  const std::vector<std::string> keys = cells_of(lines[0]);
  for (size_t r = 1; r < lines.size(); ++r) {
    const std::vector<std::string> cells = cells_of(lines[r]);
    std::map<std::string, std::string> row;
    for (size_t i = 0; i < keys.size() && i < cells.size(); ++i)
      if (keys[i] != "time/fps" && keys[i] != "time/time_elapsed") row[keys[i]] = cells[i];
    rows.push_back(row);
  }
  return rows;
}

// The monitor file's episodes: return and length (t is wall time).
std::vector<std::string> monitor_episodes(const std::string& path) {
  std::vector<std::string> episodes;
  const std::vector<std::string> lines = lines_of(read_text(path));
  for (size_t i = 2; i < lines.size(); ++i) {
    const std::vector<std::string> cells = cells_of(lines[i]);
    episodes.push_back(cells.at(0) + "," + cells.at(1));
  }
  return episodes;
}

// Both runs' files agree: every model tensor byte for byte, progress rows, monitor episodes,
// evaluations.csv.
void require_same_run(const std::string& a, const std::string& b, int n_envs, bool eval) {
  const ZipMembers model_a = read_zip(a + "/model.zip"), model_b = read_zip(b + "/model.zip");
  REQUIRE(model_a.size() == model_b.size());
  for (const auto& [name, bytes] : model_a) {
    if (name == "config.yaml") continue;  // out_dir differs
    INFO(name);
    REQUIRE(model_b.count(name) == 1);
    CHECK(bytes == model_b.at(name));
  }
  const auto rows_a = progress_rows(a + "/progress.csv"),
             rows_b = progress_rows(b + "/progress.csv");
  CHECK(rows_a.size() > 2);
  CHECK(rows_a == rows_b);
  for (int i = 0; i < n_envs; ++i) {
    // Built step by step: GCC 12 warns (-Wrestrict, a false positive) on "/" + to_string(i).
    std::string file = "/";
    file += std::to_string(i);
    file += ".monitor.csv";
    const auto episodes = monitor_episodes(a + file);
    CHECK(!episodes.empty());
    CHECK(episodes == monitor_episodes(b + file));
  }
  if (eval) {
    const std::string evaluations = read_text(a + "/evaluations.csv");
    CHECK(lines_of(evaluations).size() > 2);
    CHECK(evaluations == read_text(b + "/evaluations.csv"));
  }
}

// Starts `rlrun train`, waits for `wait_for` (a checkpoint) to appear, sends `signal` and
// returns the process's exit status line ("exit=<code>").
std::string train_then_signal(const std::string& args, const std::string& wait_for,
                              const std::string& signal, const std::string& log) {
  const std::string cmd = std::string(RLRUN_BINARY) + " --threads 1 train " + args + " > " + log +
                          " 2>&1 & pid=$!; while [ ! -e " + wait_for +
                          " ] && kill -0 $pid 2>/dev/null; do sleep 0.01; done; kill -" + signal +
                          " $pid; wait $pid; echo exit=$?";
  return run_command(cmd).output;
}

struct ResumeCase {
  std::string config;            // file under configs/
  std::string run_name;          // run.name of that file
  std::string settings;          // --set ... shortening it
  std::string first_checkpoint;  // checkpoints/step_<N>.zip that the kill waits for
  int n_envs = 1;
  bool eval = false;
};

void check_resume_equals_uninterrupted(const ResumeCase& c, const std::string& signal) {
  TempDir dir("resume_" + c.run_name + "_" + signal);
  const std::string config = std::string(RLRUN_SOURCE_DIR) + "/configs/" + c.config;
  const std::string whole = dir / "whole", cut = dir / "cut";
  const auto full =
      run_rlrun("--threads 1 train " + config + c.settings + " --set run.out_dir=" + whole);
  INFO(full.output);
  REQUIRE(full.exit_code == 0);

  const std::string run_dir = cut + "/" + c.run_name + "/seed1";
  const std::string status =
      train_then_signal(config + c.settings + " --set run.out_dir=" + cut,
                        run_dir + "/checkpoints/" + c.first_checkpoint, signal, dir / "cut.log");
  INFO(status << read_text(dir / "cut.log"));
  // SIGINT: exit 130 after writing a checkpoint at the next safe point; SIGKILL: killed.
  if (signal == "INT") {
    REQUIRE(status.find("exit=130") != std::string::npos);
    CHECK(read_text(dir / "cut.log").find("resume with: rlrun train --resume") !=
          std::string::npos);
  } else {
    REQUIRE(status.find("exit=137") != std::string::npos);
  }
  const auto resumed = run_rlrun("--threads 1 train --resume " + run_dir);
  INFO(resumed.output);
  REQUIRE(resumed.exit_code == 0);
  CHECK(resumed.output.find("resuming") != std::string::npos);
  require_same_run(whole + "/" + c.run_name + "/seed1", run_dir, c.n_envs, c.eval);
}

const ResumeCase kPpo{"cartpole_ppo.yaml",
                      "cartpole_ppo",
                      " --set run.total_timesteps=40000 --set checkpoint.freq=8192"
                      " --set eval.freq=10000 --set eval.n_episodes=3"
                      " --set 'env.wrappers=[{id: NormalizeObservation}]'",
                      "step_8192.zip",
                      8,
                      true};
const ResumeCase kSac{"pendulum_sac.yaml",
                      "pendulum_sac",
                      " --set run.total_timesteps=1600 --set algo.learning_starts=200"
                      " --set algo.batch_size=64 --set 'algo.policy.net_arch=[64, 64]'"
                      " --set checkpoint.freq=400 --set run.log_interval=1",
                      "step_400.zip",
                      1,
                      false};

// A Dict observation (MultiBinary, Discrete and Box keys) with its Box key normalised.
const ResumeCase kDictPpo{"simplemultiobs_ppo.yaml",
                          "simplemultiobs_ppo",
                          " --set checkpoint.freq=8192 --set eval.n_episodes=3"
                          " --set 'env.wrappers=[{id: NormalizeObservation}]'",
                          "step_8192.zip",
                          8,
                          true};

}  // namespace

TEST_CASE(
    "resume: PPO on a Dict observation killed after a checkpoint ends as the uninterrupted run",
    "[cli][resume][spaces]") {
  check_resume_equals_uninterrupted(kDictPpo, "KILL");
}

TEST_CASE("resume: PPO interrupted by SIGINT ends as the uninterrupted run", "[cli][resume]") {
  check_resume_equals_uninterrupted(kPpo, "INT");
}

TEST_CASE("resume: PPO killed after a checkpoint ends as the uninterrupted run", "[cli][resume]") {
  check_resume_equals_uninterrupted(kPpo, "KILL");
}

TEST_CASE("resume: SAC interrupted by SIGINT ends as the uninterrupted run (replay buffer too)",
          "[cli][resume]") {
  check_resume_equals_uninterrupted(kSac, "INT");
}

TEST_CASE("resume: SAC killed after a checkpoint ends as the uninterrupted run", "[cli][resume]") {
  check_resume_equals_uninterrupted(kSac, "KILL");
}

TEST_CASE("resume: MaskablePPO self-play on tic-tac-toe resumes with its pool of past selves",
          "[cli][resume][board_games]") {
  // Snapshots every 2048 steps (one iteration of 8 envs x 256), a checkpoint at 4096: the
  // resumed run rebuilds the pool (and the snapshots unfinished games play) from it.
  const ResumeCase self_play{"tictactoe_self_play.yaml",
                             "tictactoe_self_play",
                             " --set run.total_timesteps=12288 --set self_play.freq=2048"
                             " --set self_play.pool_size=2 --set checkpoint.freq=4096",
                             "step_4096.zip",
                             8,
                             false};
  check_resume_equals_uninterrupted(self_play, "KILL");
}

TEST_CASE("resume: DQN and TD3 runs resume exactly from a checkpoint", "[cli][resume]") {
  const ResumeCase dqn{"cartpole_dqn.yaml",
                       "cartpole_dqn",
                       " --set run.total_timesteps=3000 --set algo.learning_starts=500"
                       " --set checkpoint.freq=1000",
                       "step_1024.zip",
                       1,
                       false};
  check_resume_equals_uninterrupted(dqn, "KILL");
  const ResumeCase td3{"pendulum_td3.yaml",
                       "pendulum_td3",
                       " --set run.total_timesteps=1200 --set algo.learning_starts=200"
                       " --set algo.batch_size=64 --set 'algo.policy.net_arch=[64, 64]'"
                       " --set checkpoint.freq=400 --set run.log_interval=1",
                       "step_400.zip",
                       1,
                       false};
  check_resume_equals_uninterrupted(td3, "KILL");
}

TEST_CASE("resume: TRPO with gSDE resumes exactly (critic Adam, shuffles, conjugate gradient)",
          "[cli][resume][trpo]") {
  const ResumeCase trpo{"zoo/pendulum_trpo.yaml",
                        "trpo_Pendulum-v1",
                        " --set run.seed=1 --set run.total_timesteps=61440"
                        " --set checkpoint.freq=8192 --set eval.freq=0 --set algo.n_steps=512",
                        "step_8192.zip",
                        2,
                        false};
  check_resume_equals_uninterrupted(trpo, "KILL");
}

TEST_CASE("resume: RecurrentPPO resumes exactly (the envs' LSTM states, VecNormalize)",
          "[cli][resume][ppo_recurrent]") {
  const ResumeCase recurrent{"cartpole_novel_recurrent_ppo.yaml",
                             "cartpole_novel_recurrent_ppo",
                             " --set run.total_timesteps=4096 --set checkpoint.freq=1024"
                             " --set algo.n_epochs=2 --set algo.policy.lstm_hidden_size=16",
                             "step_1024.zip",
                             8,
                             false};
  check_resume_equals_uninterrupted(recurrent, "KILL");
}

TEST_CASE("resume: ARS with env.normalize resumes exactly (weights, directions' stream)",
          "[cli][resume][ars]") {
  const ResumeCase ars{"zoo/pendulum_ars.yaml",
                       "ars_Pendulum-v1",
                       " --set run.seed=1 --set checkpoint.freq=16000 --set eval.freq=0",
                       "step_16000.zip",
                       1,
                       false};
  check_resume_equals_uninterrupted(ars, "KILL");
}

TEST_CASE("resume: QRDQN resumes exactly from a checkpoint (the shared Q-learning state)",
          "[cli][resume][qrdqn]") {
  const ResumeCase qrdqn{"cartpole_qrdqn.yaml",
                         "cartpole_qrdqn",
                         " --set run.total_timesteps=3000 --set algo.learning_starts=500"
                         " --set checkpoint.freq=1000 --set eval.freq=0",
                         "step_1024.zip",
                         1,
                         false};
  check_resume_equals_uninterrupted(qrdqn, "KILL");
}

TEST_CASE(
    "resume: DQN on pixels with optimize_memory_usage resumes exactly (uint8 observations in the "
    "checkpoint, the buffer wrapped)",
    "[cli][resume][image]") {
  // CartPole's 36x36 gray frames (Box(0, 255, (36, 36, 1), uint8)), SB3's CnnPolicy, each
  // observation stored once, as bytes; 1 500 steps into 1 000 slots.
  const ResumeCase pixels{
      "cartpole_dqn.yaml",
      "cartpole_dqn",
      " --set run.total_timesteps=1500 --set algo.learning_starts=300 --set checkpoint.freq=500"
      " --set algo.buffer_size=1000 --set algo.optimize_memory_usage=true"
      " --set algo.handle_timeout_termination=false --set eval.freq=0"
      " --set 'env.wrappers=[{id: AddRenderObservation, width: 36, height: 36},"
      " {id: GrayscaleObservation, keep_dim: true}]'"
      " --set 'algo.policy={features_extractor_class: NatureCNN, features_dim: 32, net_arch: []}'",
      "step_512.zip",
      1,
      false};
  check_resume_equals_uninterrupted(pixels, "KILL");
}

TEST_CASE(
    "resume: SAC and TD3 with CnnPolicy resume exactly (each extractor, its target and its Adam "
    "in the checkpoint)",
    "[cli][resume][image][cnn]") {
  // Pendulum's 36x36 gray frames, the actor's and the critic's NatureCNN (SB3's off-policy
  // CnnPolicy), 900 steps with a checkpoint at 400.
  const std::string pixels =
      " --set run.total_timesteps=900 --set algo.learning_starts=200 --set algo.batch_size=16"
      " --set checkpoint.freq=400 --set run.log_interval=1 --set eval.freq=0"
      " --set 'env.wrappers=[{id: AddRenderObservation, width: 36, height: 36},"
      " {id: GrayscaleObservation, keep_dim: true}]'"
      " --set 'algo.policy={features_extractor_class: NatureCNN, features_dim: 16, net_arch: "
      "[32]}'";
  SECTION("SAC") {
    check_resume_equals_uninterrupted(
        {"pendulum_sac.yaml", "pendulum_sac", pixels, "step_400.zip", 1, false}, "KILL");
  }
  SECTION("SAC, share_features_extractor") {
    check_resume_equals_uninterrupted(
        {"pendulum_sac.yaml", "pendulum_sac",
         pixels + " --set algo.policy.share_features_extractor=true", "step_400.zip", 1, false},
        "KILL");
  }
  SECTION("TD3") {
    check_resume_equals_uninterrupted(
        {"pendulum_td3.yaml", "pendulum_td3", pixels, "step_400.zip", 1, false}, "KILL");
  }
}

TEST_CASE("resume: SAC with env.normalize resumes exactly (original observations in the buffer)",
          "[cli][resume][normalize]") {
  ResumeCase sac = kSac;
  sac.settings += " --set env.normalize=true";
  check_resume_equals_uninterrupted(sac, "KILL");
}

TEST_CASE(
    "resume: DQN with HerReplayBuffer resumes exactly (episode bookkeeping in the checkpoint)",
    "[cli][resume][her]") {
  const ResumeCase her{"bitflipping_dqn_her.yaml",
                       "bitflipping_dqn_her",
                       " --set run.total_timesteps=3000 --set checkpoint.freq=1000"
                       " --set eval.freq=0",
                       "step_1000.zip",
                       1,
                       false};
  check_resume_equals_uninterrupted(her, "KILL");
}

TEST_CASE("resume: a TQC run killed after a checkpoint ends as the uninterrupted run",
          "[cli][resume][tqc]") {
  const ResumeCase tqc{"pendulum_tqc.yaml",
                       "pendulum_tqc",
                       " --set run.total_timesteps=1200 --set algo.learning_starts=200"
                       " --set algo.batch_size=64 --set 'algo.policy.net_arch=[64, 64]'"
                       " --set checkpoint.freq=400 --set run.log_interval=1",
                       "step_400.zip",
                       1,
                       false};
  check_resume_equals_uninterrupted(tqc, "KILL");
}

// CrossQ's training state is in its model tensors too: the BatchRenorm running statistics and
// step counts (renorm_warmup_steps lowered so that the cut falls in the renorm phase).
TEST_CASE("resume: a CrossQ run killed after a checkpoint ends as the uninterrupted run",
          "[cli][resume][crossq]") {
  const ResumeCase crossq{"pendulum_crossq.yaml",
                          "pendulum_crossq",
                          " --set run.total_timesteps=1200 --set algo.learning_starts=200"
                          " --set algo.batch_size=64 --set 'algo.policy.net_arch=[64, 64]'"
                          " --set algo.policy.renorm_warmup_steps=150"
                          " --set checkpoint.freq=400 --set run.log_interval=1",
                          "step_400.zip",
                          1,
                          false};
  check_resume_equals_uninterrupted(crossq, "KILL");
}

TEST_CASE("resume: --timesteps extends a finished run from its last checkpoint", "[cli][resume]") {
  TempDir dir("resume_extend");
  const std::string config = std::string(RLRUN_SOURCE_DIR) + "/configs/cartpole_ppo.yaml";
  const auto first = run_rlrun("--threads 1 train " + config +
                               " --set run.total_timesteps=4096 --set checkpoint.freq=4096"
                               " --set run.out_dir=" +
                               dir.str());
  REQUIRE(first.exit_code == 0);
  const auto more = run_rlrun("--threads 1 train --resume " + dir / "cartpole_ppo/seed1" +
                              " --set run.total_timesteps=8192");
  INFO(more.output);
  REQUIRE(more.exit_code == 0);
  // This session's steps and rate, and where the run's count went from and to (issue 18).
  CHECK(more.output.find("trained 4096 steps (4096 -> 8192) in ") != std::string::npos);
  CHECK(read_text(dir / "cartpole_ppo/seed1/config.yaml").find("total_timesteps: 8192") !=
        std::string::npos);
  // `report`: the run's 8192 steps over both sessions' training time.
  double wall = 0;
  int sessions = 0;
  for (const std::string& line : lines_of(read_text(dir / "cartpole_ppo/seed1/log.txt")))
    if (const auto session = parse_session_summary(line)) wall += session->wall_seconds, ++sessions;
  CHECK(sessions == 2);
  char expected[96];
  std::snprintf(expected, sizeof expected, "| 8192 | %.1f | %.0f |", wall, 8192 / wall);
  const auto report = run_rlrun("report " + dir / "cartpole_ppo/seed1");
  INFO(report.output);
  CHECK(report.output.find(expected) != std::string::npos);
}

TEST_CASE("resume: refusals name the reason", "[cli][resume]") {
  TempDir dir("resume_refusals");
  const std::string config = std::string(RLRUN_SOURCE_DIR) + "/configs/cartpole_ppo.yaml";
  REQUIRE(
      run_rlrun("train " + config + " --set run.total_timesteps=512 --set run.out_dir=" + dir.str())
          .exit_code == 0);
  const std::string run_dir = dir / "cartpole_ppo/seed1";
  // No checkpoint in the run.
  auto r = run_rlrun("train --resume " + run_dir);
  CHECK(r.exit_code == 2);
  CHECK(r.output.find("no checkpoints") != std::string::npos);
  // A model file is not a checkpoint.
  r = run_rlrun("train --resume " + run_dir + "/model.zip");
  CHECK(r.exit_code == 2);
  CHECK(r.output.find("--init-from") != std::string::npos);
  // Settings other than the length cannot change.
  r = run_rlrun("train --resume " + run_dir + " --set algo.learning_rate=1e-3");
  CHECK(r.exit_code == 2);
  CHECK(r.output.find("cannot change 'algo.learning_rate=1e-3'") != std::string::npos);
  r = run_rlrun("train --resume " + dir / "nowhere");
  CHECK(r.exit_code == 2);
  CHECK(r.output.find("no such run directory") != std::string::npos);
}

TEST_CASE("divergence: a non-finite loss stops training, naming the step and the loss",
          "[cli][resume]") {
  TempDir dir("diverge");
  const std::string config = std::string(RLRUN_SOURCE_DIR) + "/configs/cartpole_ppo.yaml";
  // Rewards of 1e30 make the squared value error overflow float32 in the first update.
  const auto r = run_rlrun("train " + config +
                           " --set run.total_timesteps=4096 --set run.out_dir=" + dir.str() +
                           " --set 'env.wrappers=[{id: TransformReward, scale: 1.0e+30}]'");
  INFO(r.output);
  CHECK(r.exit_code == 1);
  CHECK(r.output.find("training diverged at step 256: train/loss is inf") != std::string::npos);
  CHECK(r.output.find("No checkpoint was written") != std::string::npos);
  CHECK_FALSE(fs::exists(dir / "cartpole_ppo/seed1/model.zip"));
}

TEST_CASE("resume: PPO with env.normalize (batched VecNormalize) resumes exactly",
          "[cli][resume][vec_normalize]") {
  // The statistics, each env's discounted return and the normalised observations of the
  // interrupted step all come back from the checkpoint.
  const ResumeCase normalized{"cartpole_ppo.yaml",
                              "cartpole_ppo",
                              " --set run.total_timesteps=20000 --set checkpoint.freq=8192"
                              " --set eval.freq=10000 --set eval.n_episodes=3"
                              " --set env.normalize=true",
                              "step_8192.zip",
                              8,
                              true};
  check_resume_equals_uninterrupted(normalized, "KILL");
}
