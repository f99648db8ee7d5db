// End-to-end tests of `rlrun train`'s options beyond --set/--seed: --timesteps, --out, -j N
// (experiments as parallel processes, Ctrl-C forwarded) and --init-from (fine-tuning from a
// trained model's weights, refused with a reason when it does not fit).
#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>

#include "rlrun/core/zip_archive.hpp"
#include "runtime/cli_runner.hpp"
#include "test_paths.hpp"

using namespace rlrun;
using namespace rlrun::testing;
namespace fs = std::filesystem;

namespace {

const std::string kConfigs = std::string(RLRUN_SOURCE_DIR) + "/configs/";

void write_text(const std::string& path, const std::string& text) {
  std::ofstream out(path);
  out << text;
}

bool contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

}  // namespace

TEST_CASE("train: --timesteps and --out set the run and are recorded in config.yaml",
          "[cli][train_options]") {
  TempDir dir("train_timesteps_out");
  const auto r = run_rlrun("train " + kConfigs + "cartpole_a2c.yaml --timesteps 3000 --out " +
                           dir / "elsewhere");
  INFO(r.output);
  REQUIRE(r.exit_code == 0);
  CHECK(contains(r.output, "trained 3000 steps"));
  const std::string config = read_text(dir / "elsewhere/cartpole_a2c/seed1/config.yaml");
  CHECK(contains(config, "total_timesteps: 3000"));
  CHECK(contains(config, "out_dir: " + dir / "elsewhere"));
}

TEST_CASE("train -j 2: several experiments as processes, failures reported",
          "[cli][train_options]") {
  TempDir dir("train_jobs");
  // A third experiment that fails at run time (its init_from file does not exist).
  write_text(dir / "broken.yaml", "run: {name: broken, init_from: " + dir / "missing.zip" +
                                      "}\nenv: {id: CartPole-v1}\nalgo: {id: PPO}\n");
  auto r =
      run_rlrun("train -j 2 " + kConfigs + "cartpole_a2c.yaml " + kConfigs + "pendulum_ppo.yaml " +
                kConfigs + "cartpole_ppo.yaml --timesteps 4096 --out " + dir / "runs");
  INFO(r.output);
  CHECK(r.exit_code == 0);
  CHECK(contains(r.output, "training 3 experiments, 2 at a time"));
  CHECK(contains(r.output, "[3/3]"));
  for (const char* name : {"cartpole_a2c", "pendulum_ppo", "cartpole_ppo"})
    CHECK(fs::exists(dir / "runs" + "/" + name + "/seed1/model.zip"));
  r = run_rlrun("train -j 2 " + kConfigs + "cartpole_a2c.yaml " + dir / "broken.yaml" +
                " --timesteps 2048 --out " + dir / "runs2");
  INFO(r.output);
  CHECK(r.exit_code == 1);
  CHECK(contains(r.output, "broken.yaml: FAILED (exit 1)"));
  CHECK(contains(r.output, "missing.zip"));
  CHECK(fs::exists(dir / "runs2/cartpole_a2c/seed1/model.zip"));
  // A failed sweep keeps its children's console logs for the user; the test removes them.
  std::smatch logs;
  REQUIRE(std::regex_search(r.output, logs,
                            std::regex("console output of each in (\\S+)/ while it runs")));
  CHECK(fs::exists(logs[1].str() + "/1.log"));
  // A private directory (mkdtemp): only its owner may enter it or plant files in it.
  CHECK((fs::status(logs[1].str()).permissions() & fs::perms::all) == fs::perms::owner_all);
  fs::remove_all(logs[1].str());
}

TEST_CASE("train -j 2: Ctrl-C reaches every run, each writes a checkpoint",
          "[cli][train_options]") {
  TempDir dir("train_jobs_sigint");
  const std::string cmd =
      std::string(RLRUN_BINARY) + " train -j 2 " + kConfigs + "cartpole_ppo.yaml " + kConfigs +
      "cartpole_a2c.yaml " + kConfigs + "pendulum_ppo.yaml --timesteps 100000000 --out " +
      dir / "runs" + " > " + dir / "out.txt" + " 2>&1 & pid=$!; while [ ! -e " +
      dir / "runs/cartpole_ppo/seed1/progress.csv" + " ] || [ ! -e " +
      dir / "runs/cartpole_a2c/seed1/progress.csv" +
      " ]; do sleep 0.05; done; sleep 0.3; kill -INT $pid; wait $pid; echo exit=$?";
  const auto r = run_command(cmd);
  const std::string out = read_text(dir / "out.txt");
  INFO(r.output << out);
  CHECK(contains(r.output, "exit=130"));
  for (const char* name : {"cartpole_ppo", "cartpole_a2c"}) {
    const std::string run_dir = dir / "runs" + "/" + name + "/seed1";
    CHECK(fs::exists(run_dir + "/model.zip"));
    CHECK(contains(out, "resume with: rlrun train --resume " + run_dir));
  }
  CHECK(contains(out, "not started: 1 experiment\n"));
}

TEST_CASE("train --init-from: starts from the model's weights", "[cli][train_options]") {
  TempDir dir("init_from");
  // A model trained on a reward-shaped CartPole ...
  REQUIRE(run_rlrun("train " + kConfigs + "cartpole_ppo.yaml --timesteps 4096 --out " +
                    dir / "shaped" +
                    " --set 'env.wrappers=[{id: TransformReward, scale: 0.5}, {id: "
                    "NormalizeObservation}]'")
              .exit_code == 0);
  const std::string model = dir / "shaped/cartpole_ppo/seed1/model.zip";
  // ... fine-tuned on the plain reward with learning rate 0: the weights stay the model's.
  const auto r =
      run_rlrun("train " + kConfigs + "cartpole_ppo.yaml --timesteps 512 --out " + dir / "tuned" +
                " --init-from " + model +
                " --set algo.learning_rate=0 --set 'env.wrappers=[{id: NormalizeObservation}]'");
  INFO(r.output);
  REQUIRE(r.exit_code == 0);
  CHECK(contains(r.output, "initialised from " + model +
                               " (PPO, CartPole-v1, 4096 steps) with its "
                               "normalisation statistics"));
  const ZipMembers before = read_zip(model);
  const ZipMembers after = read_zip(dir / "tuned/cartpole_ppo/seed1/model.zip");
  int compared = 0;
  for (const auto& [name, bytes] : before) {
    if (name.rfind("mlp_extractor", 0) != 0 && name.rfind("action_net", 0) != 0 &&
        name.rfind("value_net", 0) != 0)
      continue;
    INFO(name);
    CHECK(after.at(name) == bytes);
    ++compared;
  }
  CHECK(compared >= 8);
  CHECK(contains(read_text(dir / "tuned/cartpole_ppo/seed1/config.yaml"), "init_from: " + model));
}

TEST_CASE("train --init-from: a model that does not fit is refused with the reason",
          "[cli][train_options]") {
  TempDir dir("init_from_refused");
  REQUIRE(run_rlrun("train " + kConfigs + "cartpole_ppo.yaml --timesteps 512 --out " + dir / "m")
              .exit_code == 0);
  const std::string model = dir / "m/cartpole_ppo/seed1/model.zip";
  struct Case {
    std::string args, reason;
  };
  const Case cases[] = {
      {kConfigs + "cartpole_a2c.yaml", "it holds a PPO model, this run trains A2C"},
      {kConfigs + "pendulum_ppo.yaml", "this run's env gives Box([-1.0 -1.0 -8.0]"},
      {kConfigs + "cartpole_ppo.yaml --set 'algo.policy.net_arch=[32, 32]'",
       "has a different shape"},
  };
  for (const Case& c : cases) {
    const auto r = run_rlrun("train " + c.args + " --timesteps 512 --out " + dir / "bad" +
                             " --init-from " + model);
    INFO(c.args << "\n" << r.output);
    CHECK(r.exit_code == 2);
    CHECK(contains(r.output, "cannot initialise from " + model));
    CHECK(contains(r.output, c.reason));
  }
  // No half-made run directory is left behind.
  CHECK_FALSE(fs::exists(dir / "bad/cartpole_a2c/seed1"));
  CHECK_FALSE(fs::exists(dir / "bad/pendulum_ppo/seed1"));
}

TEST_CASE("train --init-from: fine-tune a RewardShaping model on the plain reward",
          "[cli][train_options]") {
  TempDir dir("init_from_shaping");
  // The course's shaped CartPole: a penalty while the cart stays right of 0.5 ...
  REQUIRE(run_rlrun("train " + kConfigs + "cartpole_ppo.yaml --timesteps 4096 --out " +
                    dir / "shaped" +
                    " --set 'env.wrappers=[{id: RewardShaping, terms: [{type: obs_above_for, "
                    "index: 0, threshold: 0.5, steps: 10, penalty: -1.0}]}]'")
              .exit_code == 0);
  const std::string model = dir / "shaped/cartpole_ppo/seed1/model.zip";
  // ... then the original env and reward (no wrappers at all), trained further.
  const auto r = run_rlrun("train " + kConfigs + "cartpole_ppo.yaml --timesteps 2048 --out " +
                           dir / "plain" + " --init-from " + model);
  INFO(r.output);
  REQUIRE(r.exit_code == 0);
  CHECK(contains(r.output, "initialised from " + model + " (PPO, CartPole-v1, 4096 steps)"));
  CHECK_FALSE(contains(r.output, "normalisation"));
  CHECK(contains(r.output, "trained 2048 steps"));
  const std::string run_dir = dir / "plain/cartpole_ppo/seed1";
  const std::string config = read_text(run_dir + "/config.yaml");
  CHECK_FALSE(contains(config, "RewardShaping"));
  CHECK(contains(read_text(run_dir + "/log.txt"), "initialised from " + model));
  // It trained from the loaded weights (not frozen, not restarted from scratch): the weights
  // moved away from the model's.
  const ZipMembers before = read_zip(model);
  const ZipMembers after = read_zip(run_dir + "/model.zip");
  CHECK(after.at("action_net.weight.npy") != before.at("action_net.weight.npy"));
}
