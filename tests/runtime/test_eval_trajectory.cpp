// `rlrun eval --trajectory` (runtime/run/trajectory_tap.hpp) and ModelPolicy
// (runtime/io/model_policy.hpp, the Python package's model.predict): the file holds the env's own
// observations and actions bit for bit, and a model's predict() on those observations gives
// the actions eval took.
#include <catch2/catch.hpp>
#include <cstdlib>
#include <fstream>
#include <optional>
#include <sstream>

#include "rlrun/core/config_node.hpp"
#include "rlrun/runtime/components/builtins.hpp"
#include "rlrun/runtime/io/model_policy.hpp"
#include "runtime/cli_runner.hpp"

using namespace rlrun;
using namespace rlrun::testing;

namespace {

struct Row {
  int64_t episode = 0, step = 0;
  std::vector<float> obs, action;
  double reward = 0;
  bool terminated = false, truncated = false;
};

std::vector<Row> read_trajectory(const std::string& path, int obs_dim, int act_dim) {
  std::ifstream in(path);
  std::string line;
  std::getline(in, line);
  REQUIRE(line.rfind("episode,step,obs_0,", 0) == 0);
  REQUIRE(line.find(",action_" + std::to_string(act_dim - 1) + ",reward,terminated,truncated") !=
          std::string::npos);
  std::vector<Row> rows;
  while (std::getline(in, line)) {
    std::vector<std::string> cells;
    std::stringstream s(line);
    for (std::string cell; std::getline(s, cell, ',');) cells.push_back(cell);
    REQUIRE(cells.size() == static_cast<size_t>(2 + obs_dim + act_dim + 3));
    Row row;
    row.episode = std::stoll(cells[0]);
    row.step = std::stoll(cells[1]);
    for (int i = 0; i < obs_dim; ++i) row.obs.push_back(std::strtof(cells[2 + i].c_str(), nullptr));
    for (int i = 0; i < act_dim; ++i)
      row.action.push_back(std::strtof(cells[2 + obs_dim + i].c_str(), nullptr));
    row.reward = std::strtod(cells[2 + obs_dim + act_dim].c_str(), nullptr);
    row.terminated = cells[3 + obs_dim + act_dim] == "1";
    row.truncated = cells[4 + obs_dim + act_dim] == "1";
    rows.push_back(std::move(row));
  }
  return rows;
}

EnvPtr bare_env(const std::string& id) {
  const EnvEntry& entry = *builtin_registry().find_env(id);
  return entry.make(entry.parse(ConfigNode()));
}

// Replays the file's actions on a fresh env: every observation and reward must come back
// exactly (the first episode's reset seeded, the others continuing the stream, as eval does).
void replay(const std::vector<Row>& rows, Env& env, uint64_t seed) {
  std::vector<float> obs(static_cast<size_t>(env.observation_space().flat_dim()));
  int64_t episode = -1;
  for (const Row& row : rows) {
    if (row.episode != episode) {
      env.reset(episode < 0 ? std::optional<uint64_t>(seed) : std::nullopt, obs);
      episode = row.episode;
      CHECK(row.step == 0);
    }
    REQUIRE(row.obs == obs);
    const StepResult r = env.step(row.action, obs);
    CHECK(r.reward == row.reward);
    CHECK(r.terminated == row.terminated);
  }
}

}  // namespace

TEST_CASE("cli: eval --trajectory writes the env's own observations and actions", "[cli]") {
  TempDir dir("trajectory_random");
  const std::string path = dir / "steps.csv";
  const auto r = run_rlrun(
      "eval --policy random --env CartPole-v1 --episodes 3 --seed 4 "
      "--trajectory " +
      path + " --csv " + (dir / "episodes.csv"));
  INFO(r.output);
  REQUIRE(r.exit_code == 0);
  const std::vector<Row> rows = read_trajectory(path, 4, 1);
  // One row per step of the three episodes, the last of each ending it.
  int64_t total = 0;
  std::ifstream episodes(dir / "episodes.csv");
  std::string line;
  std::getline(episodes, line);
  REQUIRE(line == "policy,episode,return,length");  // CartPole: no is_success, no metrics
  while (std::getline(episodes, line)) total += std::stoll(line.substr(line.rfind(',') + 1));
  CHECK(static_cast<int64_t>(rows.size()) == total);
  CHECK(rows.back().episode == 2);
  CHECK(rows.back().terminated);
  EnvPtr env = bare_env("CartPole-v1");
  replay(rows, *env, 4);
}

TEST_CASE(
    "cli: eval --trajectory of a model: raw observations, rescaled actions, and "
    "ModelPolicy::predict gives the same actions",
    "[cli]") {
  TempDir dir("trajectory_model");
  const std::string config = dir / "sac.yaml";
  std::ofstream(config) << "run: {name: sac, seed: 1, total_timesteps: 300, out_dir: " << dir.str()
                        << "/runs}\n"
                           "env: {id: Pendulum-v1, wrappers: [{id: NormalizeObservation},\n"
                           "  {id: RescaleAction, min_action: -0.5, max_action: 0.5}]}\n"
                           "algo: {id: SAC, learning_starts: 100, batch_size: 32,\n"
                           "       policy: {net_arch: [16, 16]}}\n";
  const auto t = run_rlrun("train " + config);
  INFO(t.output);
  REQUIRE(t.exit_code == 0);
  const std::string model = dir / "runs/sac/seed1/model.zip";
  const std::string path = dir / "steps.csv";
  const auto e = run_rlrun("eval --model " + model + " --episodes 1 --seed 7 --trajectory " + path);
  INFO(e.output);
  REQUIRE(e.exit_code == 0);
  const std::vector<Row> rows = read_trajectory(path, 3, 1);
  REQUIRE(rows.size() == 200);            // Pendulum's time limit
  CHECK(rows.back().truncated == false);  // the TimeLimit above the tap cuts the episode
  EnvPtr env = bare_env("Pendulum-v1");
  replay(rows, *env, 7);  // observations before NormalizeObservation

  // The policy acts in [-0.5, 0.5]; the file holds Pendulum's actions in [-2, 2] (sampled
  // actions reach beyond the policy's bounds).
  const std::string sampled = dir / "sampled.csv";
  REQUIRE(run_rlrun("eval --model " + model + " --stochastic --episodes 1 --trajectory " + sampled)
              .exit_code == 0);
  bool beyond_policy_bounds = false;
  for (const Row& row : read_trajectory(sampled, 3, 1)) {
    CHECK(row.action[0] >= -2.0f);
    CHECK(row.action[0] <= 2.0f);
    beyond_policy_bounds = beyond_policy_bounds || std::abs(row.action[0]) > 0.5f;
  }
  CHECK(beyond_policy_bounds);

  ModelPolicy policy(model, builtin_registry());
  CHECK(policy.meta().algorithm == "SAC");
  CHECK(policy.observation_space().describe() == env->observation_space().describe());
  Eigen::MatrixXf obs(3, 1), action;
  for (const Row& row : rows) {
    std::copy(row.obs.begin(), row.obs.end(), obs.data());
    policy.predict(obs, /*deterministic=*/true, action);
    REQUIRE(action.rows() == 1);
    REQUIRE(action(0, 0) == row.action[0]);
  }
}
