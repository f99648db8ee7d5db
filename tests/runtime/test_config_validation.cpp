// Every bad value is refused up front: before any run directory exists or anything trains,
// with file:line:col, the key path and, for names, a did-you-mean; a file with several problems
// reports them all (the security review's items 5, 6, 10 and 11; Env API v2's typed configs).
#include <catch2/catch.hpp>
#include <chrono>
#include <filesystem>
#include <fstream>

#include "runtime/cli_runner.hpp"
#include "test_paths.hpp"

using namespace rlrun::testing;
namespace fs = std::filesystem;

namespace {

const std::string kConfigs = std::string(RLRUN_SOURCE_DIR) + "/configs";

std::string write_config(const TempDir& dir, const std::string& name, const std::string& text) {
  const std::string path = dir / name;
  std::ofstream(path) << text;
  return path;
}

// Runs `train` and checks it refused (exit 2) without creating any run directory.
CommandResult refused(const TempDir& dir, const std::string& args) {
  const auto start = std::chrono::steady_clock::now();
  const CommandResult r = run_rlrun("train --set run.out_dir=" + dir / "runs" + " " + args);
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  INFO(r.output);
  CHECK(r.exit_code == 2);
  CHECK_FALSE(fs::exists(dir / "runs"));
  CHECK(seconds < 30);  // refused, not attempted (a generous bound: no timing is asserted)
  return r;
}

bool has(const CommandResult& r, const std::string& text) {
  return r.output.find(text) != std::string::npos;
}

}  // namespace

TEST_CASE("validation: a later file's error stops everything before the first file trains",
          "[cli][config]") {
  TempDir dir("validate_late");
  const std::string bad =
      write_config(dir, "acrobot_bad.yaml",
                   "env: {id: Acrobot-v1}\nalgo:\n  id: DQN\n  policy: {activation_fn: nn.Relu}\n");
  const auto r = refused(dir, kConfigs + "/cartpole_ppo.yaml " + bad);
  CHECK(has(r,
            "acrobot_bad.yaml:4:27: algo.policy.activation_fn: unknown activation 'nn.Relu' "
            "(did you mean 'nn.ReLU'?)"));
  CHECK_FALSE(has(r, "training"));
  // A critic key of the off-policy algorithms in a PPO entry: SB3 would ignore it silently.
  const auto qf =
      refused(dir, kConfigs + "/cartpole_ppo.yaml --set 'algo.policy.net_arch={pi: [8], qf: [8]}'");
  CHECK(has(qf, "algo.policy.net_arch.qf: unknown key 'qf'"));
  CHECK(has(qf, "valid keys: pi, vf"));
  CHECK_FALSE(has(qf, "training"));
}

TEST_CASE("validation: a file with three problems reports all three", "[cli][config]") {
  TempDir dir("validate_three");
  const std::string path = write_config(dir, "three.yaml",
                                        "run: {total_timesteps: 1000}\n"
                                        "env: {id: CartPole-v1, wrapers: []}\n"
                                        "algo: {id: PPO, gamma: 2, clip_range: -0.2}\n");
  const auto r = refused(dir, path);
  CHECK(has(r, "three.yaml:2:24: env.wrapers: unknown key 'wrapers' (did you mean 'wrappers'?)"));
  CHECK(has(r,
            "valid keys: n_envs, max_episode_steps, auto_wrap, python, startup_timeout, opponent, "
            "learner_side, agent_indicator, agent_policies, info_keywords, normalize, id, kwargs, "
            "wrappers"));
  CHECK(has(r, "three.yaml:3:24: algo.gamma: must be in [0, 1], got 2"));
  CHECK(has(r, "three.yaml:3:39: algo.clip_range: must be > 0, got -0.2"));
}

TEST_CASE("validation: values SB3 or sense refuse", "[cli][config]") {
  TempDir dir("validate_values");
  const std::string ppo = kConfigs + "/cartpole_ppo.yaml";
  const std::string dqn = kConfigs + "/cartpole_dqn.yaml";
  const std::vector<std::pair<std::string, std::string>> cases{
      {ppo + " --set algo.gamma=-0.5", "algo.gamma: must be in [0, 1], got -0.5"},
      {ppo + " --set algo.learning_rate=-1", "algo.learning_rate: must be >= 0, got -1"},
      {dqn + " --set algo.exploration_fraction=2",
       "algo.exploration_fraction: must be in (0, 1], got 2"},
      {ppo + " --set run.console_interval=-1", "run.console_interval: must be in [0, "},
      {ppo + " --set env.max_episode_steps=0", "env.max_episode_steps: must be >= 1, got 0"},
      {ppo + " --set env.max_episode_steps=-1", "env.max_episode_steps: must be >= 1, got -1"},
      {ppo + " --set 'run.name=\"\"'", "run.name: must not be empty"},
      {ppo + " --set 'run.out_dir=\"\"'", "run.out_dir: must not be empty"},
      {ppo + " --set run.name=../../x", "run.name: must not contain empty, '.' or '..' parts"},
      {ppo + " --set run.name=..", "run.name: must not contain empty, '.' or '..' parts"},
      {ppo + " --set run.name=/tmp/x", "run.name: must be a relative name"},
      {ppo + " --set 'run.name=\"nul\\0byte\"'", "run.name: must not contain control characters"},
      {ppo + " --set algo.gamma=.nan", "NaN is not a setting"},
      // Infinity as NaN, also where no range would catch it (Pendulum's gravity g has none).
      {kConfigs + "/pendulum_ppo.yaml --timesteps 64 --set env.kwargs.g=.inf",
       "--set env.kwargs.g=.inf: env.kwargs.g: expected a finite number, got '.inf' (infinity is "
       "not a setting)"},
      {ppo + " --timesteps 64 --set algo.learning_rate=inf",
       "algo.learning_rate: expected a finite number or lin_<number>, got 'inf'"},
      {ppo + " --timesteps 64 --set env.startup_timeout=0",
       "env.startup_timeout: must be in (0, 1000000]"},
      {ppo + " --set run.seed=-1", "run.seed: expected a non-negative integer"},
      {ppo + " --set video.freq=1000 --set video.width=100000 --set video.height=100000",
       "video.width: must be in [0, 4096], got 100000"},
  };
  for (const auto& [args, message] : cases) {
    const auto r = refused(dir, args);
    INFO(args);
    CHECK(has(r, message));
  }
}

TEST_CASE("validation: duplicate keys and second documents are refused", "[cli][config]") {
  TempDir dir("validate_yaml");
  const auto dup = refused(dir, write_config(dir, "dup.yaml",
                                             "env: {id: CartPole-v1}\nalgo: {id: PPO}\n"
                                             "algo: {id: A2C}\n"));
  CHECK(has(dup, "dup.yaml:3:1: key 'algo' repeats the one at line 2, column 1"));
  const auto second = refused(dir, write_config(dir, "two.yaml",
                                                "env: {id: CartPole-v1}\nalgo: {id: PPO}\n---\n"
                                                "algo: {id: A2C}\n"));
  CHECK(has(second, "a second YAML document"));
  // yaml-cpp loops forever on a stray flow character that starts a document (LoadAll); the
  // loader stops and names it (a fuzz find: a comment whose line was broken in two).
  const auto stray = refused(dir, write_config(dir, "stray.yaml",
                                               "# net_arch [400\n, 300] (a broken comment)\n"
                                               "env: {id: CartPole-v1}\n"));
  CHECK(has(stray, "stray.yaml:2:1: invalid YAML: a ',', ']' or '}' outside any [list] or {map}"));
  CHECK(has(refused(dir, kConfigs + "/cartpole_ppo.yaml --set 'algo.n_steps=, 5'"),
            "--set algo.n_steps=, 5"));
}

TEST_CASE("validation: sizes that would take the machine are refused with their key",
          "[cli][config]") {
  TempDir dir("validate_sizes");
  const std::string ppo = kConfigs + "/cartpole_ppo.yaml";
  CHECK(has(refused(dir, ppo + " --set 'env.wrappers=[{id: FrameStack, n_stack: 1e8}]'"),
            "env.wrappers[0].n_stack: must be in [1, 1000], got 100000000"));
  CHECK(has(refused(dir, ppo + " --set env.n_envs=100000"), "env.n_envs: must be in [1, 4096]"));
  CHECK(has(refused(dir, ppo + " --set 'algo.policy.net_arch=[100000, 100000]'"),
            "algo.policy.net_arch[0]: must be in [1, 65536], got 100000"));
  CHECK(has(refused(dir, ppo + " --set 'algo.policy.net_arch=[60000, 60000]'"),
            "algo.policy.net_arch: this network needs"));
  CHECK(has(refused(dir, kConfigs + "/pendulum_sac.yaml --set algo.buffer_size=1e12"),
            "algo.buffer_size: a replay buffer of 1000000000000 transitions needs"));
  // A 5 MB list under an unknown key is refused by size, before it is parsed.
  std::string big = "env: {id: CartPole-v1}\nalgo: {id: PPO}\njunk: [";
  while (big.size() < 5'000'000) big += "1234567, ";
  big += "0]\n";
  CHECK(has(refused(dir, write_config(dir, "big.yaml", big)), "big.yaml: larger than 1 MiB"));
  // Aliases that expand to billions of values.
  const std::string laughs = "env: {id: CartPole-v1}\nalgo: {id: PPO}\n" + yaml_alias_bomb();
  CHECK(
      has(refused(dir, write_config(dir, "laughs.yaml", laughs)), "more than 100000 YAML values"));
}

TEST_CASE("validation: a sweep of 10^8 runs is refused before it is expanded", "[cli][config]") {
  TempDir dir("validate_sweep");
  std::string grid;
  for (const char* key : {"gamma", "gae_lambda", "ent_coef", "vf_coef", "max_grad_norm", "n_epochs",
                          "batch_size", "n_steps"})
    grid +=
        std::string(grid.empty() ? "" : ", ") + "algo." + key + ": [1, 2, 3, 4, 5, 6, 7, 8, 9, 10]";
  const std::string sweep =
      write_config(dir, "huge.yaml",
                   "base: " + kConfigs + "/cartpole_ppo.yaml\nout_dir: " + dir / "out" +
                       "\ngrid: {" + grid + "}\n");
  const auto r = run_rlrun("sweep " + sweep);
  INFO(r.output);
  CHECK(r.exit_code == 2);
  CHECK(has(r, "the grid gives 100000000 runs"));
  CHECK_FALSE(fs::exists(dir / "out"));
}

TEST_CASE("validation: eval --baseline that does not fit the env is refused before any episode",
          "[cli][config]") {
  TempDir dir("validate_baseline");
  REQUIRE(run_rlrun("train " + kConfigs + "/cartpole_ppo.yaml --set run.total_timesteps=256" +
                    " --set run.out_dir=" + dir.str())
              .exit_code == 0);
  const auto r = run_rlrun("eval --model " + dir / "cartpole_ppo/seed1/model.zip" +
                           " --baseline fixed-time --episodes 3");
  INFO(r.output);
  CHECK(r.exit_code == 2);
  CHECK_FALSE(has(r, "mean_reward"));
}
