// What rlrun prints, read as a new user reads it (issue 41, "Output"): no fps from a
// near-zero interval, the counts of a multi-agent run explained, baselines' rewards that mean
// something, several policies in one table.
#include <catch2/catch.hpp>

#include <cmath>
#include <fstream>
#include <sstream>

#include "rlrun/algos/common/session_time.hpp"
#include "rlrun/runtime/io/log_sinks.hpp"
#include "runtime/cli_runner.hpp"
#include "test_paths.hpp"

using namespace rlrun;
using namespace rlrun::testing;

namespace {

// progress.csv as rows of column -> cell text.
std::vector<std::map<std::string, std::string>> csv_rows(const std::string& path) {
  std::ifstream in(path);
  std::string line;
  std::getline(in, line);
  const std::vector<std::string> header = split_csv_line(line);
  std::vector<std::map<std::string, std::string>> rows;
  while (std::getline(in, line)) {
    const std::vector<std::string> cells = split_csv_line(line);
    std::map<std::string, std::string> row;
    for (size_t i = 0; i < header.size() && i < cells.size(); ++i) row[header[i]] = cells[i];
    rows.push_back(row);
  }
  return rows;
}

}  // namespace

TEST_CASE("output: time/fps only over an interval of at least 0.1 s", "[output]") {
  Logger log;
  record_session_time(log, 0.0004, 256);  // CartPole's first rollout, before any training
  CHECK(log.pending().count("time/fps") == 0);
  CHECK(log.pending().at("time/time_elapsed") == 0);
  record_session_time(log, 2.5, 5000);
  CHECK(log.pending().at("time/fps") == 2000);
  CHECK(log.pending().at("time/time_elapsed") == 2);
}

// The first row of a run comes after 16 CartPole steps: SB3's formula made that hundreds of
// thousands of steps per second. A row's fps may not claim more than its steps over 0.1 s.
TEST_CASE("output: the first progress row of a fast run has no absurd fps", "[output][cli]") {
  TempDir dir("output_fps");
  const auto r = run_rlrun("train " + std::string(RLRUN_SOURCE_DIR) +
                           "/configs/cartpole_ppo.yaml --timesteps 64 --out " + dir.str() +
                           " --set env.n_envs=1 --set algo.n_steps=16 --set algo.batch_size=16");
  INFO(r.output);
  REQUIRE(r.exit_code == 0);
  const auto rows = csv_rows(dir / "cartpole_ppo/seed1/progress.csv");
  REQUIRE(rows.size() == 4);
  for (const auto& row : rows) {
    const double steps = std::stod(row.at("time/total_timesteps"));
    const auto fps = row.find("time/fps");
    if (fps != row.end() && !fps->second.empty()) CHECK(std::stod(fps->second) <= steps / 0.1);
  }
}

// TrafficNetwork-v0's 16 lights are 16 agents: 8 env steps per episode (40 s / 5 s) are 128
// timesteps. The console says how each count counts before the first table.
TEST_CASE("output: a multi-agent run says what its step counts count",
          "[output][cli][traffic_network]") {
  TempDir dir("output_agents");
  const auto r = run_command("SUMO_HOME=/usr/share/sumo " + std::string(RLRUN_BINARY) + " train " +
                             RLRUN_SOURCE_DIR +
                             "/configs/traffic_network_ppo.yaml --timesteps 128 "
                             "--out " +
                             dir.str() +
                             " --set env.kwargs.num_seconds=40 "
                             "--set algo.n_steps=8 --set algo.batch_size=32");
  INFO(r.output);
  REQUIRE(r.exit_code == 0);
  CHECK(r.output.find("note: TrafficNetwork-v0 has 16 agents sharing one policy: each env step "
                      "counts as 16 timesteps") != std::string::npos);
  CHECK(r.output.find("ep_len_mean counts env steps") != std::string::npos);
  CHECK(r.output.find("note: TrafficNetwork-v0 has") < r.output.find("| rollout/"));
  const auto rows = csv_rows(dir / "traffic_network_ppo/seed1/progress.csv");
  REQUIRE(rows.size() == 1);
  CHECK(rows[0].at("rollout/ep_len_mean") == "8");
  CHECK(rows[0].at("time/total_timesteps") == "128");
  // A single-agent run has no such note.
  const auto single = run_rlrun("train " + std::string(RLRUN_SOURCE_DIR) +
                                "/configs/cartpole_ppo.yaml --timesteps 256 --out " + dir.str());
  CHECK(single.output.find("agents sharing") == std::string::npos);
}

// The network's baselines hand the lights to SUMO; the reward (diff-waiting-time, from the
// vehicles on each light's incoming lanes) was then not computed and eval printed
// mean_reward = 0.00. It is the env's reward under every control.
TEST_CASE("output: TrafficNetwork-v0's baselines get the env's reward",
          "[output][cli][traffic_network]") {
  for (const char* policy : {"fixed-time", "actuated"}) {
    const auto r = run_command("SUMO_HOME=/usr/share/sumo " + std::string(RLRUN_BINARY) +
                               " eval --env TrafficNetwork-v0 --episodes 1 --policy " + policy +
                               " --set env.kwargs.num_seconds=300");
    INFO(r.output);
    REQUIRE(r.exit_code == 0);
    const size_t at = r.output.find("mean_reward = ");
    REQUIRE(at != std::string::npos);
    CHECK(std::stod(r.output.substr(at + 14)) < 0);  // waiting time grows from an empty network
  }
}

// Baselines side by side: one row per policy, the env's metrics as columns, every policy on the
// same episodes (so two random policies, seeded alike, give the same row).
TEST_CASE("output: eval --policy with several names compares them in one table", "[output][cli]") {
  TempDir dir("output_policies");
  const auto r = run_rlrun(
      "eval --env GripperReach-v0 --policy scripted,random,random --episodes 3 "
      "--csv " +
      dir / "episodes.csv");
  INFO(r.output);
  REQUIRE(r.exit_code == 0);
  std::vector<std::string> lines;
  std::istringstream in(r.output);
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  REQUIRE(lines.size() == 6);
  CHECK(lines[0] ==
        "scripted,random,random on GripperReach-v0, 3 episodes each from seed 0 (the "
        "same episodes for every policy):");
  CHECK(lines[1] ==
        "| policy   | mean_reward | std_reward | mean_ep_length | success_rate | distance |");
  CHECK(lines[3].rfind("| scripted | ", 0) == 0);
  CHECK(lines[3].find("| 1.000        |") != std::string::npos);  // the scripted reach succeeds
  CHECK(lines[4].rfind("| random   | ", 0) == 0);
  CHECK(lines[4] == lines[5]);
  // --csv: every episode of every policy (the single-policy layout).
  const std::string csv = read_text(dir / "episodes.csv");
  CHECK(csv.rfind("policy,episode,return,length,is_success,distance\n", 0) == 0);
  CHECK(std::count(csv.begin(), csv.end(), '\n') == 1 + 3 * 3);
  // One policy: the summary lines as before; a list with an empty name or --trajectory: refused.
  const auto one = run_rlrun("eval --env GripperReach-v0 --policy scripted --episodes 3");
  CHECK(one.output.rfind("scripted on GripperReach-v0, 3 episodes: mean_reward = ", 0) == 0);
  CHECK(run_rlrun("eval --env GripperReach-v0 --policy scripted,").exit_code == 2);
  const auto trajectory = run_rlrun(
      "eval --env GripperReach-v0 --policy scripted,random "
      "--trajectory " +
      dir / "t.csv");
  CHECK(trajectory.exit_code == 2);
  CHECK(trajectory.output.find("give --policy one name") != std::string::npos);
}
