// Issue 6's bar for Grasp2D-v0: configs/grasp2d_ppo.yaml and configs/grasp2d_dqn.yaml train,
// through the real binary, a policy whose success rate over 100 deterministic evaluation
// episodes (`rlrun eval --csv`, column is_success) is at least 0.95. Slow (PPO ~25 s, DQN
// ~90 s on two cores): hidden tag, run with `rlrun_tests "[grasp2d_learning]"`.
#include <unistd.h>

#include <catch2/catch.hpp>
#include <fstream>
#include <sstream>
#include <string>

#include "runtime/cli_runner.hpp"
#include "test_paths.hpp"

using namespace rlrun::testing;

namespace {

// Mean of the is_success column of `rlrun eval --csv` (policy,episode,return,length,
// is_success, then the env's metrics).
double success_rate(const std::string& csv_path) {
  std::ifstream in(csv_path);
  std::string line;
  std::getline(in, line);
  REQUIRE(line.rfind("policy,episode,return,length,is_success", 0) == 0);
  int n = 0;
  double sum = 0;
  while (std::getline(in, line)) {
    std::stringstream row(line);
    std::string cell;
    for (int column = 0; column <= 4; ++column) std::getline(row, cell, ',');
    sum += std::stod(cell);
    ++n;
  }
  REQUIRE(n == 100);
  return sum / n;
}

double train_and_measure(const std::string& config, const std::string& name) {
  TempDir dir(name + "_" + std::to_string(getpid()));
  const auto train = run_rlrun("train " + std::string(RLRUN_SOURCE_DIR) + "/configs/" + config +
                               " --set run.out_dir=" + dir.str() + " --set eval.freq=0");
  INFO(train.output.substr(train.output.size() > 3000 ? train.output.size() - 3000 : 0));
  REQUIRE(train.exit_code == 0);
  const std::string model = dir / (config.substr(0, config.find('.')) + "/seed1/model.zip");
  const auto eval =
      run_rlrun("eval --model " + model + " --episodes 100 --seed 1000 --csv " + dir / "eval.csv");
  INFO(eval.output);
  REQUIRE(eval.exit_code == 0);
  return success_rate(dir / "eval.csv");
}

}  // namespace

TEST_CASE("grasp2d learning: PPO config reaches 0.95 success", "[.slow][grasp2d_learning]") {
  CHECK(train_and_measure("grasp2d_ppo.yaml", "grasp2d_ppo") >= 0.95);
}

TEST_CASE("grasp2d learning: DQN config reaches 0.95 success", "[.slow][grasp2d_learning]") {
  CHECK(train_and_measure("grasp2d_dqn.yaml", "grasp2d_dqn") >= 0.95);
}
