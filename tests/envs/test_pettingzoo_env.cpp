// pettingzoo:<module>:<function> envs (src/rlrun/envs/python/pettingzoo_agents.py): PettingZoo
// envs written in Python, trained by the real rlrun binary with real worker processes. The envs
// are tests/python_envs/rlrun_test_envs/multi_agent.py and turn_game.py (PettingZoo's API
// without PettingZoo; tests/python/test_pettingzoo.py runs PettingZoo's own envs when it is
// installed).
#include <catch2/catch.hpp>
#include <filesystem>
#include <map>
#include <regex>
#include <string>

#include "envs/python_env_runner.hpp"

using namespace rlrun::testing;

namespace {

const std::string kHoming = "pettingzoo:rlrun_test_envs.multi_agent:parallel_env";
const std::string kTurnTicTacToe = "pettingzoo:rlrun_test_envs.turn_game:env";

// "mean_reward = X" of `rlrun eval`'s summary.
double mean_reward(const std::string& output) {
  std::smatch m;
  REQUIRE(std::regex_search(output, m, std::regex("mean_reward = (-?[0-9.]+)")));
  return std::stod(m[1]);
}

}  // namespace

TEST_CASE("A parallel PettingZoo env: its agents share one policy, PPO learns it", "[python]") {
  TempDir dir("pettingzoo_parallel");
  const CommandResult check =
      run_rlrun_python("check-env " + kHoming + " --episodes 20 --python " + kPython);
  INFO(check.output);
  REQUIRE(check.exit_code == 0);
  CHECK(check.output.find("agents             3") != std::string::npos);
  const double random_return =
      mean_reward(run_rlrun_python("eval --env " + kHoming +
                                   " --policy random --episodes 50 --set env.python=" + kPython)
                      .output);

  // Agents that reach home leave early (black death until the episode ends): a walker that
  // goes straight home scores 1 - 0.1 x (steps - 1); three of them about 2.5.
  const std::string config = python_experiment(
      dir.str(), "homing", kHoming,
      "id: PPO, n_steps: 128, batch_size: 64, n_epochs: 4, learning_rate: 0.001, ent_coef: 0.01",
      30000, 2);
  const CommandResult train = run_rlrun_python("train " + config);
  INFO(train.output);
  REQUIRE(train.exit_code == 0);
  CHECK(train.output.find("3 agents sharing one policy") != std::string::npos);
  const CommandResult eval = run_rlrun_python("eval --model " + dir.str() +
                                              "/runs/homing/seed1/model.zip --episodes 50 --trust");
  INFO(eval.output);
  REQUIRE(eval.exit_code == 0);
  CHECK(random_return < 0.0);
  CHECK(mean_reward(eval.output) > 1.8);
}

TEST_CASE("A turn-based PettingZoo game: MaskablePPO keeps to the mask and beats a random seat",
          "[python]") {
  TempDir dir("pettingzoo_turns");
  // The env raises on an illegal move: check-env's random player and training keep to the mask.
  const CommandResult check =
      run_rlrun_python("check-env " + kTurnTicTacToe + " --episodes 20 --python " + kPython);
  INFO(check.output);
  REQUIRE(check.exit_code == 0);

  // opponent: self (PettingZoo's SB3 tutorial): one policy plays both seats.
  const std::string self_play =
      python_experiment(dir.str(), "self_play", kTurnTicTacToe,
                        "id: MaskablePPO, n_steps: 64, batch_size: 64", 2000, 2);
  const CommandResult trained_self = run_rlrun_python("train " + self_play);
  INFO(trained_self.output);
  REQUIRE(trained_self.exit_code == 0);

  // opponent: random, the learner's seat alternating: +1 a win, -1 a loss.
  const std::string config = python_experiment(
      dir.str(), "vs_random", kTurnTicTacToe, "id: MaskablePPO, n_steps: 128, batch_size: 64",
      30000, 4, ", opponent: random, learner_side: alternate");
  const CommandResult train = run_rlrun_python("train " + config);
  INFO(train.output);
  REQUIRE(train.exit_code == 0);
  const std::string model = dir.str() + "/runs/vs_random/seed1/model.zip";
  const double random_vs_random =
      mean_reward(run_rlrun_python("eval --env " + kTurnTicTacToe +
                                   " --policy random --episodes 200 --set env.python=" + kPython +
                                   " --set env.opponent=random")
                      .output);
  const CommandResult eval = run_rlrun_python("eval --model " + model + " --episodes 200 --trust");
  INFO(eval.output);
  REQUIRE(eval.exit_code == 0);
  CHECK(mean_reward(eval.output) > random_vs_random + 0.3);
}

TEST_CASE("rlrun record films a PettingZoo game through its render(), padding an odd frame",
          "[python]") {
  TempDir dir("pettingzoo_record");
  const std::string video = dir.str() + "/game.mp4";
  const CommandResult r = run_rlrun_python("record --env " + kTurnTicTacToe +
                                           " --policy random --episodes 1 --output " + video +
                                           " --set env.python=" + kPython);
  INFO(r.output);
  REQUIRE(r.exit_code == 0);
  // The env's 33 x 31 frame (no render_mode in the kwargs: rlrun asked for rgb_array, as
  // raw_env's metadata offers it) in a 34 x 32 video.
  CHECK(r.output.find("at 34x32") != std::string::npos);
  CHECK(std::filesystem::file_size(video) > 0);
}

TEST_CASE("PettingZoo agents whose spaces differ are refused with the reason", "[python]") {
  const CommandResult r = run_rlrun_python(
      "check-env pettingzoo:rlrun_test_envs.multi_agent:uneven_env --python " + kPython);
  CHECK(r.exit_code != 0);
  CHECK(r.output.find("the agents' spaces differ ('walker_0' and 'walker_2')") !=
        std::string::npos);
  CHECK(r.output.find("pad_action_space_v0") != std::string::npos);
  const CommandResult bad =
      run_rlrun_python("check-env pettingzoo:not-a-module --python " + kPython);
  CHECK(bad.exit_code != 0);
  CHECK(bad.output.find("is not a PettingZoo env id: write pettingzoo:<module>:<function>") !=
        std::string::npos);
}

TEST_CASE("A PettingZoo env that breaks the API's contract gets a clear error, not a crash",
          "[python]") {
  // Each factory of tests/python_envs/rlrun_test_envs/multi_agent.py breaks one rule; check-env
  // stops with the worker's reason.
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"duplicate_agents_env", "possible_agents name 'walker_0' more than once"},
      {"missing_agent_env", "step() returned no observations for the live agent(s) ['walker_0']"},
      {"unknown_agent_env",
       "step() returned rewards for ['ghost'], which possible_agents does not"},
      {"unknown_live_agent_env", "after step() env.agents holds ['ghost']"},
  };
  for (const auto& [factory, message] : cases) {
    INFO(factory);
    const CommandResult r = run_rlrun_python(
        "check-env pettingzoo:rlrun_test_envs.multi_agent:" + factory + " --python " + kPython);
    INFO(r.output);
    CHECK(r.exit_code != 0);
    CHECK(r.output.find(message) != std::string::npos);
    CHECK(r.output.find("Traceback") == std::string::npos);
  }
}

TEST_CASE("env.agent_indicator: the shared policy tells the agents apart (SuperSuit's layout)",
          "[python]") {
  // Sides: two walkers start in the middle and must walk to opposite ends, seeing only their
  // position. Without an indicator the one policy sends both the same way (one gets home, 0.8;
  // the other never does, -1.2: about -0.4 together); with it both get home (1.6 together).
  TempDir dir("pettingzoo_indicator");
  const std::string sides = "pettingzoo:rlrun_test_envs.multi_agent:sides_env";
  std::map<std::string, double> returns;
  for (const std::string indicator : {"none", "agent"}) {
    const std::string config = python_experiment(
        dir.str(), "sides_" + indicator, sides,
        "id: PPO, n_steps: 128, batch_size: 64, n_epochs: 4, learning_rate: 0.001", 20000, 2,
        ", agent_indicator: " + indicator);
    if (indicator == "agent") {  // a one-hot column per agent after the position
      const CommandResult check = run_rlrun_python("check-env " + config);
      INFO(check.output);
      REQUIRE(check.exit_code == 0);
      CHECK(check.output.find("Box(0.0, 1.0, (3,), float32)") != std::string::npos);
    }
    const CommandResult train = run_rlrun_python("train " + config);
    INFO(train.output);
    REQUIRE(train.exit_code == 0);
    const CommandResult eval =
        run_rlrun_python("eval --model " + dir.str() + "/runs/sides_" + indicator +
                         "/seed1/model.zip --episodes 20 --trust");
    INFO(eval.output);
    REQUIRE(eval.exit_code == 0);
    returns[indicator] = mean_reward(eval.output);
  }
  INFO("without " << returns["none"] << ", with " << returns["agent"]);
  CHECK(returns["agent"] > 1.5);
  CHECK(returns["none"] < 0.5);
  // type: one indicator per <type>_<n> agent type; Homing's walkers are one type.
  const std::string typed =
      python_experiment(dir.str(), "typed", kHoming, "id: PPO", 1000, 1, ", agent_indicator: type");
  const CommandResult check = run_rlrun_python("check-env " + typed + " --episodes 2");
  INFO(check.output);
  CHECK(check.exit_code == 0);
  CHECK(check.output.find("(3,), float32)") != std::string::npos);
}
