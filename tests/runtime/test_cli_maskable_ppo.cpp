// MaskablePPO through the real binary: the shipped GridWorld config trains and evaluates to
// the optimum, and Python envs report masks through action_masks() or info["action_mask"]
// (tests/python_envs/rlrun_test_envs/masked.py raises on an illegal action).
#include <unistd.h>

#include <catch2/catch.hpp>
#include <regex>
#include <string>

#include "envs/python_env_runner.hpp"
#include "runtime/cli_runner.hpp"
#include "test_paths.hpp"

using namespace rlrun::testing;

namespace {
const std::string kLegalPick = "python:rlrun_test_envs.masked:LegalPick";
const std::string kMaskablePPO = "id: MaskablePPO, n_steps: 32, batch_size: 32, n_epochs: 2";
}  // namespace

TEST_CASE("MaskablePPO: the GridWorld config trains, and eval and record use its masks",
          "[ppo_mask][cli][grid_world]") {
  TempDir dir("gridworld_maskable_ppo_" + std::to_string(getpid()));
  const auto train =
      run_rlrun("train " + std::string(RLRUN_SOURCE_DIR) +
                "/configs/gridworld_maskable_ppo.yaml --set run.out_dir=" + dir.str());
  INFO(train.output.substr(train.output.size() > 3000 ? train.output.size() - 3000 : 0));
  REQUIRE(train.exit_code == 0);
  const std::string progress = read_text(dir / "gridworld_maskable_ppo/seed1/progress.csv");
  for (const char* key : {"train/entropy_loss", "train/clip_fraction", "train/n_updates"})
    CHECK(progress.find(key) != std::string::npos);
  CHECK(progress.find("train/std") == std::string::npos);
  const std::string model = dir / "gridworld_maskable_ppo/seed1/model.zip";
  const auto eval = run_rlrun("eval --model " + model + " --episodes 5");
  INFO(eval.output);
  REQUIRE(eval.exit_code == 0);
  CHECK(eval.output.find("mean_reward = -8.00 +/- 0.00, mean_ep_length = 8.0") !=
        std::string::npos);
  // Stochastic episodes with the masks never bump into the wall: every move is -1, so the
  // return is minus the length.
  const auto stochastic = run_rlrun("eval --model " + model + " --episodes 20 --stochastic");
  INFO(stochastic.output);
  REQUIRE(stochastic.exit_code == 0);
  std::smatch m;
  REQUIRE(std::regex_search(stochastic.output, m,
                            std::regex("mean_reward = (-?[0-9.]+) \\+/- [0-9.]+, "
                                       "mean_ep_length = ([0-9.]+)")));
  CHECK(std::stod(m[1].str()) == Approx(-std::stod(m[2].str())).margin(0.06));
  const auto record = run_rlrun("record --model " + model + " --frames " + dir / "frames" +
                                " --episodes 3 --stochastic");
  INFO(record.output);
  CHECK(record.exit_code == 0);
  CHECK(record.output.find("(MaskablePPO stochastic)") != std::string::npos);
  // Export writes the unmasked deterministic policy and says so.
  const auto exported =
      run_rlrun("export --model " + model + " --format c --output " + dir / "policy_c");
  INFO(exported.output);
  CHECK(exported.exit_code == 0);
  CHECK(exported.output.find("takes no action masks") != std::string::npos);
  const auto list = run_rlrun("list MaskablePPO");
  CHECK(list.exit_code == 0);
  CHECK(list.output.find("target_kl") != std::string::npos);
}

TEST_CASE("MaskablePPO trains a Python env's masks from action_masks() or info action_mask",
          "[ppo_mask][python]") {
  TempDir dir("python_masks");
  for (const std::string kwargs : {"", ", kwargs: {mask_in_info: true}"}) {
    INFO(kwargs);
    const std::string config =
        python_experiment(dir.str(), "legal_pick", kLegalPick, kMaskablePPO, 256, 2, kwargs);
    const auto r = run_rlrun_python("train " + config);
    INFO(r.output);
    CHECK(r.exit_code == 0);
    const auto eval = run_rlrun_python("eval --model " + dir / "runs/legal_pick/seed1/model.zip" +
                                       " --episodes 3 --stochastic --trust");
    INFO(eval.output);
    CHECK(eval.exit_code == 0);
  }
  // PPO has no masks: it soon takes an illegal action, which the env refuses.
  const std::string unmasked = python_experiment(dir.str(), "legal_pick_ppo", kLegalPick,
                                                 "id: PPO, n_steps: 32, batch_size: 32", 256, 2);
  CHECK(run_rlrun_python("train " + unmasked).output.find("illegal action") != std::string::npos);
}

TEST_CASE("a Python env's empty or wrong-length mask is an error naming the env and step",
          "[ppo_mask][python]") {
  TempDir dir("python_bad_masks");
  const std::string empty = python_experiment(dir.str(), "empty", kLegalPick, kMaskablePPO, 256, 1,
                                              ", kwargs: {empty_at: 5}");
  const auto r = run_rlrun_python("train " + empty);
  INFO(r.output);
  CHECK(r.exit_code == 1);
  CHECK(r.output.find("(env 0) at step 5: the action mask allows no action") != std::string::npos);
  const std::string longer = python_experiment(dir.str(), "longer", kLegalPick, kMaskablePPO, 256,
                                               1, ", kwargs: {mask_length: 6}");
  const auto l = run_rlrun_python("train " + longer);
  INFO(l.output);
  CHECK(l.exit_code == 1);
  CHECK(l.output.find("(env 0) after reset(): the env reports an action mask of 6 entries, "
                      "MaskablePPO needs 4") != std::string::npos);
}
