// The board games through the command line: a short MaskablePPO run on tic-tac-toe beats the
// random player clearly, `eval --opponent/--side` reports win/draw/loss rates, and a short
// self-play run snapshots its policy into a pool whose checkpoints can then be the opponent.
// (The issue's bars take minutes of training: scripts/bench/board_games.sh.)
#include <catch2/catch.hpp>
#include <regex>
#include <string>

#include "runtime/cli_runner.hpp"
#include "test_paths.hpp"

using namespace rlrun::testing;

namespace {

// The mean of `key` in an eval summary ("  win = 0.950 (mean over episodes)"), or -1.
double rate(const std::string& output, const std::string& key) {
  const std::regex line("\\n  " + key + " = ([0-9.]+) \\(mean");
  std::smatch m;
  return std::regex_search(output, m, line) ? std::stod(m[1]) : -1.0;
}

std::string config(const std::string& name) {
  return std::string(RLRUN_SOURCE_DIR) + "/configs/" + name;
}

}  // namespace

TEST_CASE("board games training: a short MaskablePPO run beats the random player at tic-tac-toe",
          "[board_games][cli]") {
  TempDir dir("tictactoe_smoke");
  const auto train = run_rlrun("train " + config("tictactoe_maskable_ppo.yaml") +
                               " --set run.total_timesteps=30000 --set env.kwargs.opponent=random"
                               " --set env.kwargs.opponent_random_moves=0"
                               " --set algo.learning_rate=1e-3 --set run.out_dir=" +
                               dir.str());
  INFO(train.output.substr(train.output.size() > 3000 ? train.output.size() - 3000 : 0));
  REQUIRE(train.exit_code == 0);
  const std::string model = dir / "tictactoe_maskable_ppo/seed1/model.zip";
  const auto eval = run_rlrun("eval --model " + model +
                              " --episodes 200 --opponent random --side alternate --seed 3");
  INFO(eval.output);
  REQUIRE(eval.exit_code == 0);
  CHECK(rate(eval.output, "win") >= 0.75);
  CHECK(rate(eval.output, "loss") <= 0.1);
  CHECK(rate(eval.output, "illegal_move") == 0.0);
  CHECK(rate(eval.output, "learner_first") == 0.5);
  // The same model against perfect play, second: it cannot win.
  const auto perfect =
      run_rlrun("eval --model " + model + " --episodes 20 --opponent minimax:9 --side second");
  INFO(perfect.output);
  REQUIRE(perfect.exit_code == 0);
  CHECK(rate(perfect.output, "win") == 0.0);
  CHECK(rate(perfect.output, "learner_first") == 0.0);
  const auto bad = run_rlrun("eval --model " + model + " --opponent minimax:x");
  CHECK(bad.exit_code != 0);
  CHECK(bad.output.find("minimax:N") != std::string::npos);
}

TEST_CASE("board games training: self-play fills a pool, its checkpoints play as opponents",
          "[board_games][cli]") {
  TempDir dir("tictactoe_self_play");
  const auto train = run_rlrun("train " + config("tictactoe_self_play.yaml") +
                               " --set run.total_timesteps=8192 --set self_play.freq=2048"
                               " --set checkpoint.freq=4096 --set run.out_dir=" +
                               dir.str());
  INFO(train.output.substr(train.output.size() > 3000 ? train.output.size() - 3000 : 0));
  REQUIRE(train.exit_code == 0);
  const std::string run = dir / "tictactoe_self_play/seed1";
  CHECK(read_text(run + "/config.yaml").find("latest_probability") != std::string::npos);
  const auto eval =
      run_rlrun("eval --model " + run + "/model.zip --episodes 50 --opponent model:" + run +
                "/checkpoints/step_4096.zip --side first");
  INFO(eval.output);
  REQUIRE(eval.exit_code == 0);
  CHECK(rate(eval.output, "win") + rate(eval.output, "draw") + rate(eval.output, "loss") ==
        Approx(1.0));
  // Self-play needs an env that plays a pool opponent.
  const auto refused = run_rlrun("train " + config("gridworld_maskable_ppo.yaml") +
                                 " --set self_play.freq=100 --set run.out_dir=" + dir.str());
  CHECK(refused.exit_code != 0);
  CHECK(refused.output.find("plays no opponent from a policy pool") != std::string::npos);
}
