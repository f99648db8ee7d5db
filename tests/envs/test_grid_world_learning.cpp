// Issue 6's bar for GridWorld-v0: configs/gridworld_dqn.yaml (10k steps, a few seconds)
// learns the shortest path, so the deterministic evaluation return is the optimum, -8.
#include <unistd.h>

#include <catch2/catch.hpp>
#include <regex>
#include <string>

#include "runtime/cli_runner.hpp"
#include "test_paths.hpp"

using namespace rlrun::testing;

TEST_CASE("grid world learning: DQN config returns the optimum", "[grid_world][cli]") {
  TempDir dir("gridworld_dqn_" + std::to_string(getpid()));
  const auto train = run_rlrun("train " + std::string(RLRUN_SOURCE_DIR) +
                               "/configs/gridworld_dqn.yaml --set run.out_dir=" + dir.str());
  INFO(train.output.substr(train.output.size() > 3000 ? train.output.size() - 3000 : 0));
  REQUIRE(train.exit_code == 0);
  const auto eval =
      run_rlrun("eval --model " + dir / "gridworld_dqn/seed1/model.zip" + " --episodes 5");
  INFO(eval.output);
  REQUIRE(eval.exit_code == 0);
  CHECK(eval.output.find("mean_reward = -8.00 +/- 0.00, mean_ep_length = 8.0") !=
        std::string::npos);
  CHECK(eval.output.find("success_rate = 1.000") != std::string::npos);
}
