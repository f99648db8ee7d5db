// End-to-end tests of the rlrun binary, run as a user would.
#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>

#include "rlrun/core/zip_archive.hpp"
#include "runtime/cli_runner.hpp"
#include "test_paths.hpp"

using namespace rlrun::testing;
namespace fs = std::filesystem;

namespace {

void write_file(const std::string& path, const std::string& text) {
  std::ofstream out(path);
  out << text;
}

std::string first_line(const std::string& path) {
  std::ifstream in(path);
  std::string line;
  std::getline(in, line);
  return line;
}

double parse_mean_reward(const std::string& output) {
  std::smatch m;
  REQUIRE(std::regex_search(output, m, std::regex("mean_reward = (-?[0-9.]+)")));
  return std::stod(m[1]);
}

const std::string kSource = RLRUN_SOURCE_DIR;

}  // namespace

TEST_CASE("cli: list shows the registry", "[cli]") {
  const auto r = run_rlrun("list");
  CHECK(r.exit_code == 0);
  for (const char* id : {"CartPole-v1", "Pendulum-v1", "MountainCar-v0", "MountainCarContinuous-v0",
                         "Acrobot-v1", "PPO"})
    CHECK(r.output.find(id) != std::string::npos);
  const auto p = run_rlrun("list PPO");
  CHECK(p.exit_code == 0);
  CHECK(p.output.find("clip_range") != std::string::npos);
  // The policy section's options are rows of their own, each with its default and doc.
  // (the column is as wide as the longest name, policy.features_extractor_class)
  const auto row = [&](const std::string& name) {
    const size_t at = p.output.find(name + " ");
    return at == std::string::npos ? std::string()
                                   : p.output.substr(at, p.output.find('\n', at) - at);
  };
  CHECK_THAT(row("policy.net_arch"), Catch::Matches("policy\\.net_arch +\\[64, 64\\] .*"));
  CHECK_THAT(row("policy.ortho_init"), Catch::Matches("policy\\.ortho_init +true .*"));
  CHECK_THAT(row("policy.features_extractor_class"),
             Catch::Matches("policy\\.features_extractor_class +FlattenExtractor .*"));
  CHECK(run_rlrun("list PPOO").exit_code == 2);
}

TEST_CASE("cli: a YAML typo exits 2 naming file:line:col and the suggested key", "[cli]") {
  TempDir dir("typo");
  const std::string path = dir / "typo.yaml";
  write_file(path, "env:\n  id: CartPole-v1\nalgo:\n  id: PPO\n  n_stpes: 32\n");
  const auto r = run_rlrun("train " + path);
  CHECK(r.exit_code == 2);
  CHECK(r.output.find(path + ":5:3") != std::string::npos);
  CHECK(r.output.find("did you mean 'n_steps'") != std::string::npos);
  // Unknown ids and bad overrides are usage errors too.
  write_file(path, "env: {id: CartPole-v2}\nalgo: {id: PPO}\n");
  const auto id = run_rlrun("train " + path);
  CHECK(id.exit_code == 2);
  CHECK(id.output.find("did you mean 'CartPole-v1'") != std::string::npos);
  write_file(path, "env: {id: CartPole-v1}\nalgo: {id: PPO}\n");
  const auto set = run_rlrun("train " + path + " --set algo.n_steps=many");
  CHECK(set.exit_code == 2);
  CHECK(set.output.find("--set algo.n_steps=many") != std::string::npos);
  CHECK(run_rlrun("train").exit_code == 2);
  CHECK(run_rlrun("train " + dir / "missing.yaml").exit_code == 2);
}

TEST_CASE("cli: train writes the run directory, eval needs only the model file", "[cli]") {
  TempDir dir("train");
  const std::string config = dir / "tiny.yaml";
  write_file(config, "run: {name: tiny, seed: 3, total_timesteps: 4096, out_dir: " + dir.str() +
                         "/runs}\n"
                         "env: {id: CartPole-v1, n_envs: 2}\n"
                         "algo: {id: PPO, n_steps: 64, batch_size: 32, n_epochs: 2}\n"
                         "eval: {freq: 2048, n_episodes: 3}\n");
  const auto r = run_rlrun("train " + config);
  INFO(r.output);
  REQUIRE(r.exit_code == 0);
  const std::string run = dir / "runs/tiny/seed3";
  for (const char* f : {"config.yaml", "progress.csv", "0.monitor.csv", "1.monitor.csv", "log.txt",
                        "model.zip", "evaluations.csv", "best_model.zip"})
    CHECK(fs::exists(run + "/" + f));
  const std::string header = first_line(run + "/progress.csv");
  // (time/fps comes only from rows 0.1 s or more into the run: algos/common/session_time.hpp.)
  for (const char* key :
       {"time/total_timesteps", "rollout/ep_rew_mean", "rollout/ep_len_mean", "train/value_loss",
        "train/approx_kl", "train/clip_fraction", "train/entropy_loss", "train/learning_rate"})
    CHECK(header.find(key) != std::string::npos);
  CHECK(first_line(run + "/0.monitor.csv").rfind("#{\"t_start\": ", 0) == 0);
  CHECK(read_text(run + "/config.yaml").find("gae_lambda: 0.95") != std::string::npos);
  CHECK(read_text(run + "/log.txt").find("model saved to") != std::string::npos);
  // evaluations.csv: header + 2 evaluations (at 2048 and 4096 steps).
  const std::string evals = read_text(run + "/evaluations.csv");
  CHECK(std::count(evals.begin(), evals.end(), '\n') == 3);

  // A second run with the same name never overwrites the first.
  REQUIRE(run_rlrun("train " + config + " --set run.total_timesteps=256").exit_code == 0);
  CHECK(fs::exists(dir / "runs/tiny/seed3_2/model.zip"));

  // eval from a different working directory, with nothing but the model file.
  const std::string csv = dir / "episodes.csv";
  const auto e = run_rlrun("eval --model " + run + "/model.zip --episodes 4 --seed 5 --csv " + csv);
  INFO(e.output);
  CHECK(e.exit_code == 0);
  CHECK(e.output.find("mean_reward = ") != std::string::npos);
  const std::string rows = read_text(csv);
  CHECK(std::count(rows.begin(), rows.end(), '\n') == 5);
  // One tidy table (docs: eval --csv): a policy column always, one row per episode.
  CHECK(rows.rfind("policy,episode,return,length\nPPO,0,", 0) == 0);
  CHECK(rows.find("mean") == std::string::npos);
  CHECK(run_rlrun("eval --model " + run + "/model.zip --stochastic --episodes 2").exit_code == 0);
  // Same seed, deterministic policy: same result.
  CHECK(run_rlrun("eval --model " + run + "/model.zip --episodes 2 --seed 9").output ==
        run_rlrun("eval --model " + run + "/model.zip --episodes 2 --seed 9").output);
}

TEST_CASE("cli: eval refuses files that are not models of this format", "[cli]") {
  TempDir dir("refuse");
  CHECK(run_rlrun("eval --model " + dir / "none.zip").exit_code == 1);
  write_file(dir / "junk.zip", "not a zip");
  const auto junk = run_rlrun("eval --model " + dir / "junk.zip");
  CHECK(junk.exit_code == 1);
  CHECK(junk.output.find("not a readable model file") != std::string::npos);
  const std::string meta = R"({"format_version": 99, "rlrun_version": "9.0.0", "algorithm": "PPO",
    "env_id": "CartPole-v1", "observation_space": "", "action_space": "", "num_timesteps": 0})";
  rlrun::write_zip_atomic(
      dir / "future.zip",
      {{"meta.json", std::vector<uint8_t>(meta.begin(), meta.end())}, {"config.yaml", {}}});
  const auto future = run_rlrun("eval --model " + dir / "future.zip");
  CHECK(future.exit_code == 1);
  CHECK(future.output.find("format version 99") != std::string::npos);
}

TEST_CASE("cli: SB3 users' tools read the outputs (pandas load_results, numpy.load)",
          "[cli][python]") {
  TempDir dir("python");
  const auto r =
      run_rlrun("train " + kSource + "/configs/cartpole_ppo.yaml --set run.out_dir=" + dir.str() +
                " --set run.total_timesteps=2048");
  REQUIRE(r.exit_code == 0);
  const std::string run = dir / "cartpole_ppo/seed1";
  const auto monitor =
      run_command("/usr/bin/python3 " + kSource + "/tests/data/sb3_load_results.py " + run);
  INFO(monitor.output);
  CHECK(monitor.exit_code == 0);
  CHECK(monitor.output.find("env_id=CartPole-v1") != std::string::npos);
  const auto model = run_command("/usr/bin/python3 " + kSource +
                                 "/tests/data/numpy_load_model.py " + run + "/model.zip");
  INFO(model.output);
  CHECK(model.exit_code == 0);
  CHECK(model.output.find("mlp_extractor.policy_net.0.weight float32 (64, 4)") !=
        std::string::npos);
  CHECK(model.output.find("action_net.weight float32 (2, 64)") != std::string::npos);
  CHECK(model.output.find("value_net.bias float32 (1,)") != std::string::npos);
}

// Learning bars at rl-zoo's budgets (10 deterministic evaluation episodes per seed).
// The walking-skeleton issue asks every seed of cartpole_ppo to reach 475; the algorithms
// issue asks each config to reach its task's bar in at least 2 of 3 seeds. Only configs that
// train in a few seconds run here; the slower ones are in learning_slow below.
namespace {
int seeds_reaching(const std::string& config, double bar, TempDir& dir) {
  int reached = 0;
  for (int seed : {1, 2, 3}) {
    const auto train = run_rlrun("train " + kSource + "/configs/" + config + ".yaml --seed " +
                                 std::to_string(seed) + " --set run.out_dir=" + dir.str());
    REQUIRE(train.exit_code == 0);
    const auto eval = run_rlrun("eval --model " + dir.str() + "/" + config + "/seed" +
                                std::to_string(seed) + "/model.zip --episodes 10");
    const double mean = parse_mean_reward(eval.output);
    UNSCOPED_INFO(config << " seed " << seed << ": " << mean);
    reached += mean >= bar;
  }
  return reached;
}
}  // namespace

TEST_CASE("learning: configs/cartpole_ppo.yaml reaches 475 for seeds 1, 2, 3", "[cli][learning]") {
  TempDir dir("learning_ppo");
  CHECK(seeds_reaching("cartpole_ppo", 475.0, dir) == 3);
}

TEST_CASE("learning: fast configs reach their bar in at least 2 of 3 seeds", "[cli][learning]") {
  TempDir dir("learning_fast");
  CHECK(seeds_reaching("cartpole_a2c", 475.0, dir) >= 2);
  CHECK(seeds_reaching("pendulum_ppo", -200.0, dir) >= 2);
}

TEST_CASE("cli: Ctrl-C stops training cleanly and keeps the model", "[cli]") {
  TempDir dir("sigint");
  // Start a long run in the background, interrupt it a moment after it says it trains (its
  // handlers are in place then; a background job starts with SIGINT ignored, so a Ctrl-C
  // before would be lost, as it was under ASan's slow start).
  const std::string cmd = std::string(RLRUN_BINARY) + " train " + kSource +
                          "/configs/cartpole_ppo.yaml --set run.total_timesteps=100000000 "
                          "--set run.out_dir=" +
                          dir.str() + " > " + dir / "out.txt" +
                          " 2>&1 & pid=$!; for i in $(seq 600); do grep -q 'training PPO' " +
                          dir / "out.txt" +
                          " && break; sleep 0.05; done; sleep 0.5; "
                          "kill -INT $pid; wait $pid; echo exit=$?";
  const auto r = run_command(cmd);
  INFO(r.output << read_text(dir / "out.txt"));
  CHECK(r.output.find("exit=130") != std::string::npos);
  CHECK(fs::exists(dir / "cartpole_ppo/seed1/model.zip"));
  CHECK(read_text(dir / "out.txt").find("interrupted") != std::string::npos);
  // The interrupted model is a valid model file.
  CHECK(run_rlrun("eval --model " + dir / "cartpole_ppo/seed1/model.zip --episodes 1").exit_code ==
        0);
}

TEST_CASE("cli: a mistyped command is named with the command meant", "[cli]") {
  auto r = run_rlrun("trian configs/cartpole_ppo.yaml");
  CHECK(r.exit_code == 2);
  CHECK(r.output == "error: unknown command 'trian'; did you mean 'train'?\n");
  r = run_rlrun("--threads 1 evl --model x.zip");
  CHECK(r.exit_code == 2);
  CHECK(r.output.find("unknown command 'evl'; did you mean 'eval'?") != std::string::npos);
  r = run_rlrun("frobnicate");
  CHECK(r.exit_code == 2);
  CHECK(r.output.find("unknown command 'frobnicate'; the commands are train, eval, list") !=
        std::string::npos);
  r = run_rlrun("");
  CHECK(r.exit_code == 2);
  CHECK(r.output.find("a command is required: train, eval") != std::string::npos);
  r = run_rlrun("sweep rnu manifest.yaml");
  CHECK(r.exit_code == 2);
  CHECK(r.output.find("rlrun sweep: unknown command 'rnu'; did you mean 'run'?") !=
        std::string::npos);
  // Unexpected arguments in the order they were typed (CLI11 2.1 reverses them).
  r = run_rlrun("sweep s.yaml --colour always");
  CHECK(r.exit_code == 2);
  CHECK(r.output.find("rlrun sweep: unexpected arguments: --colour always") != std::string::npos);
  r = run_rlrun("sweep status manifest.yaml --frob");
  CHECK(r.exit_code == 2);
  CHECK(r.output.find("rlrun sweep status: unexpected argument '--frob'") != std::string::npos);
  CHECK(run_rlrun("--version").exit_code == 0);
  CHECK(run_rlrun("train --help").exit_code == 0);
}

TEST_CASE("cli: counts say 1 episode, 1 env", "[cli]") {
  const auto eval = run_rlrun("eval --env CartPole-v1 --policy random --episodes 1");
  INFO(eval.output);
  CHECK(eval.exit_code == 0);
  CHECK(eval.output.find("random on CartPole-v1, 1 episode: mean_reward") != std::string::npos);
  TempDir dir("cli_plurals");
  const auto train =
      run_rlrun("train " + kSource + "/configs/cartpole_ppo.yaml --set env.n_envs=1 " +
                "--set algo.n_steps=64 --set algo.batch_size=64 --timesteps 64 --out " + dir.str());
  INFO(train.output);
  CHECK(train.exit_code == 0);
  CHECK(train.output.find("for 64 steps (seed 1, 1 env, ") != std::string::npos);
}
