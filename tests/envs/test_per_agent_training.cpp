// env.agent_policies: per_agent (src/rlrun/runtime/run/per_agent_training.hpp): one learner per
// agent of a multi-agent env, trained by the real rlrun binary on a Python PettingZoo env with
// real worker processes, then played as a team by `rlrun eval --model <run dir>`. The team file
// (agents.json) is read as untrusted input: a run_dir that leaves the run directory, or a model
// behind a link, is refused.
#include <catch2/catch.hpp>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <regex>
#include <string>

#include "envs/python_env_runner.hpp"

using namespace rlrun::testing;
namespace fs = std::filesystem;

namespace {

const std::string kSides = "pettingzoo:rlrun_test_envs.multi_agent:sides_env";
const std::string kPpo = "id: PPO, n_steps: 128, batch_size: 64, n_epochs: 4, learning_rate: 0.001";

double mean_reward(const std::string& output) {
  std::smatch m;
  REQUIRE(std::regex_search(output, m, std::regex("mean_reward = (-?[0-9.]+)")));
  return std::stod(m[1]);
}

}  // namespace

TEST_CASE("env.agent_policies: per_agent: each walker learns its own way home, played as a team",
          "[python][per_agent]") {
  // Sides (tests/python_envs/rlrun_test_envs/multi_agent.py): two walkers that see only their
  // position must walk to opposite ends. One shared policy without an indicator sends both the
  // same way (about -0.4 together, test_pettingzoo_env.cpp); two learners can each learn their
  // own walker's way (1.6 together).
  TempDir dir("per_agent_sides");
  const std::string config =
      python_experiment(dir.str(), "sides", kSides, kPpo, 12000, 2, ", agent_policies: per_agent");
  const CommandResult train = run_rlrun_python("train " + config);
  INFO(train.output);
  REQUIRE(train.exit_code == 0);
  const std::string team = dir.str() + "/runs/sides/seed1";
  // The team's directory: its config, log and team file; each learner's complete run directory.
  for (const char* file : {"config.yaml", "log.txt", "agents.json", "finished"})
    CHECK(fs::is_regular_file(team + "/" + file));
  for (const char* learner : {"agents/walker_0/seed1", "agents/walker_1/seed2"})
    for (const char* file : {"model.zip", "progress.csv", "config.yaml"}) {
      INFO(learner << "/" << file);
      CHECK(fs::is_regular_file(team + "/" + learner + "/" + file));
    }
  const std::string agents = read_text(team + "/agents.json");
  CHECK(agents.find("\"run_dir\": \"agents/walker_1/seed2\"") != std::string::npos);
  CHECK(read_text(team + "/log.txt").find("one PPO learner per agent") != std::string::npos);

  const CommandResult eval = run_rlrun_python("eval --model " + team + " --episodes 20 --trust");
  INFO(eval.output);
  REQUIRE(eval.exit_code == 0);
  CHECK(eval.output.find("one per agent (2 agents)") != std::string::npos);
  CHECK(mean_reward(eval.output) > 1.5);
  // The team file itself names the team too.
  const CommandResult by_file =
      run_rlrun_python("eval --model " + team + "/agents.json --episodes 2 --trust");
  INFO(by_file.output);
  CHECK(by_file.exit_code == 0);

  // `rlrun report <team>` reports its agents' runs (the team directory has no data of its own).
  const CommandResult report = run_rlrun_python("report " + team);
  INFO(report.output);
  CHECK(report.exit_code == 0);
  CHECK(report.output.find("| walker_0 | 1 (1) |") != std::string::npos);
  CHECK(report.output.find("| walker_1 | 1 (2) |") != std::string::npos);

  // A per-agent run cannot be resumed (its learners' checkpoints hold their models only).
  const CommandResult resume = run_rlrun_python("train --resume " + team);
  INFO(resume.output);
  CHECK(resume.exit_code != 0);
  CHECK(resume.output.find("cannot be resumed") != std::string::npos);
}

TEST_CASE("env.agent_policies: per_agent refuses what it cannot do, before anything runs",
          "[python][per_agent]") {
  TempDir dir("per_agent_refusals");
  const std::vector<std::pair<std::string, std::string>> cases{
      {python_experiment(dir.str(), "wrapped", kSides, "id: PPO", 1000, 1,
                         ", agent_policies: per_agent, wrappers: [{id: TransformReward, "
                         "scale: 2}]"),
       "per_agent does not support env.wrappers"},
      {python_experiment(dir.str(), "indicator", kSides, "id: PPO", 1000, 1,
                         ", agent_policies: per_agent, agent_indicator: agent"),
       "per_agent does not support env.agent_indicator"},
      {python_experiment(dir.str(), "single", "CartPole-v1", "id: PPO", 1000, 1,
                         ", agent_policies: per_agent"),
       "CartPole-v1 has one agent"},
      {python_experiment(dir.str(), "typo", kSides, "id: PPO", 1000, 1,
                         ", agent_policies: per_agents"),
       "per_agent"},
  };
  for (const auto& [config, message] : cases) {
    const CommandResult r = run_rlrun_python("train " + config);
    INFO(r.output);
    CHECK(r.exit_code != 0);
    CHECK(r.output.find(message) != std::string::npos);
    CHECK(!fs::exists(dir.str() + "/runs/wrapped/seed1/agents"));
  }
}

TEST_CASE("A per-agent run's agents.json is untrusted: paths outside the run, links, junk",
          "[per_agent][security]") {
  TempDir dir("per_agent_team_file");
  const std::string team = dir.str() + "/team";
  fs::create_directories(team + "/agents/a/seed1");
  fs::create_directories(dir.str() + "/elsewhere");
  std::ofstream(dir.str() + "/elsewhere/model.zip") << "not a model";
  const auto team_file = [&](const std::string& run_dir_a) {
    std::ofstream(team + "/agents.json")
        << R"({"format": "rlrun agents", "version": 1, "env": "X-v0", "algorithm": "PPO",
               "agents": [{"name": "a", "run_dir": ")"
        << run_dir_a << R"("}, {"name": "b", "run_dir": "agents/a/seed1"}]})";
  };
  const auto eval = [&] { return run_rlrun_python("eval --model " + team + " --episodes 1"); };

  team_file("../elsewhere");
  CommandResult r = eval();
  INFO(r.output);
  CHECK(r.exit_code != 0);
  CHECK(r.output.find("not a relative path of plain names") != std::string::npos);

  team_file(dir.str() + "/elsewhere");  // absolute
  r = eval();
  INFO(r.output);
  CHECK(r.output.find("not a relative path of plain names") != std::string::npos);

  fs::create_directory_symlink(dir.str() + "/elsewhere", team + "/agents/linked");
  team_file("agents/linked");  // a directory link on the way
  r = eval();
  INFO(r.output);
  CHECK(r.exit_code != 0);
  CHECK(r.output.find("link") != std::string::npos);
  CHECK(r.output.find("elsewhere/model.zip") == std::string::npos);

  fs::create_symlink(dir.str() + "/elsewhere/model.zip", team + "/agents/a/seed1/model.zip");
  team_file("agents/a/seed1");  // the model file a link
  r = eval();
  INFO(r.output);
  CHECK(r.exit_code != 0);
  CHECK(r.output.find("not a link") != std::string::npos);

  std::ofstream(team + "/agents.json") << R"({"format": "rlrun agents", "version": 9})";
  r = eval();
  INFO(r.output);
  CHECK(r.exit_code != 0);
  CHECK(r.output.find("version 9 is not one this rlrun reads") != std::string::npos);

  std::ofstream(team + "/agents.json") << "[1, 2";
  r = eval();
  INFO(r.output);
  CHECK(r.exit_code != 0);
  CHECK(r.output.find("is not JSON") != std::string::npos);

  fs::remove(team + "/agents.json");  // the team file itself a link
  fs::create_symlink(dir.str() + "/elsewhere/model.zip", team + "/agents.json");
  r = eval();
  INFO(r.output);
  CHECK(r.exit_code != 0);
  CHECK(r.output.find("Segmentation") == std::string::npos);
}

TEST_CASE("env.agent_policies: per_agent on TrafficNetwork-v0: one learner per traffic light",
          "[traffic_network][per_agent]") {
  // Real SUMO: the 4x4 grid's 16 lights, each trained by its own PPO for two short rollouts,
  // then played as a team against max-pressure on the same episodes.
  TempDir dir("per_agent_traffic");
  const std::string config =
      write_file(dir.str() + "/grid.yaml",
                 "run: {name: grid, seed: 3, total_timesteps: 256, out_dir: " + dir.str() +
                     "/runs}\n"
                     "env: {id: TrafficNetwork-v0, agent_policies: per_agent, kwargs: {scenario: " +
                     kSourceDir +
                     "/scenarios/grid4x4.yaml, delta_time: 5, num_seconds: 300}}\n"
                     "algo: {id: PPO, n_steps: 64, batch_size: 32, n_epochs: 2}\n");
  const CommandResult train = run_rlrun_python("train " + config);
  INFO(train.output);
  REQUIRE(train.exit_code == 0);
  const std::string team = dir.str() + "/runs/grid/seed3";
  // Lights A0 ... D3, learner i seeded 3 + i in the env's agent order.
  CHECK(fs::is_regular_file(team + "/agents/A0/seed3/model.zip"));
  CHECK(fs::is_regular_file(team + "/agents/D3/seed18/model.zip"));
  const CommandResult eval =
      run_rlrun_python("eval --model " + team + " --episodes 1 --baseline max-pressure");
  INFO(eval.output);
  REQUIRE(eval.exit_code == 0);
  CHECK(eval.output.find("PPO, one per agent (16 agents) on TrafficNetwork-v0") !=
        std::string::npos);
  CHECK(eval.output.find("max-pressure on TrafficNetwork-v0") != std::string::npos);
}

TEST_CASE("A real city network SUMO's package ships: baselines, and one learner per light",
          "[traffic_network][per_agent]") {
  // tools/game/DRT/osm.net.xml of Debian's sumo-tools: imported from OpenStreetMap, 15 lights,
  // ids of joined OSM nodes up to 170 characters. Demand: randomTrips.py with a fixed seed.
  const char* home = std::getenv("SUMO_HOME");
  const std::string sumo_home = home && *home ? home : "/usr/share/sumo";
  const std::string net = sumo_home + "/tools/game/DRT/osm.net.xml";
  REQUIRE(fs::is_regular_file(net));  // Debian package sumo-tools (scripts/setup.sh)
  TempDir dir("per_agent_osm");
  const std::string routes = dir.str() + "/drt.rou.xml";
  const CommandResult trips = run_command(
      "/usr/bin/python3 " + sumo_home + "/tools/randomTrips.py -n " + net +
      " -b 0 -e 900 -p 1.5 --fringe-factor 10 --min-distance 300 --seed 3 --validate -o " +
      dir.str() + "/trips.xml -r " + routes);
  INFO(trips.output);
  REQUIRE(trips.exit_code == 0);
  const std::string scenario =
      write_file(dir.str() + "/drt.yaml", "name: drt\nnet_file: " + net + "\nroute_files: [" +
                                              routes + "]\nbegin: 0\nend: 900\n");
  const CommandResult baselines =
      run_rlrun_python("eval --env TrafficNetwork-v0 --set env.kwargs.scenario=" + scenario +
                       " --policy fixed-time,max-pressure --episodes 1");
  INFO(baselines.output);
  REQUIRE(baselines.exit_code == 0);
  CHECK(baselines.output.find("| max-pressure |") != std::string::npos);

  const std::string config =
      write_file(dir.str() + "/drt_ppo.yaml",
                 "run: {name: drt, seed: 1, total_timesteps: 128, out_dir: " + dir.str() +
                     "/runs}\n"
                     "env: {id: TrafficNetwork-v0, agent_policies: per_agent, kwargs: {scenario: " +
                     scenario + "}}\nalgo: {id: PPO, n_steps: 64, batch_size: 32, n_epochs: 1}\n");
  const CommandResult train = run_rlrun_python("train " + config);
  INFO(train.output);
  REQUIRE(train.exit_code == 0);
  const std::string team = dir.str() + "/runs/drt/seed1";
  int learners = 0;
  for (const auto& entry : fs::directory_iterator(team + "/agents")) {
    ++learners;
    CHECK(entry.path().filename().string().size() <= 96);  // the long cluster ids cut
  }
  CHECK(learners == 15);
  const CommandResult eval = run_rlrun_python("eval --model " + team + " --episodes 1 --trust");
  INFO(eval.output);
  REQUIRE(eval.exit_code == 0);
  CHECK(eval.output.find("PPO, one per agent (15 agents) on TrafficNetwork-v0") !=
        std::string::npos);
}
