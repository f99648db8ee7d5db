// GripperLift-v0's speed (issue 8: >= 3 000 env steps/s on one core) and SAC's training speed
// on it. Measured, not asserted (docs/benchmarks.md): `build/tests/rlrun_tests "[gripper_bench]"`,
// run by scripts/bench.sh.
#include <catch2/catch.hpp>
#include <chrono>
#include <cstdio>
#include <ctime>
#include <regex>
#include <string>
#include <vector>

#include "rlrun/envs/gripper/gripper_goal_env.hpp"
#include "rlrun/envs/gripper/gripper_lift.hpp"
#include "rlrun/envs/gripper/scripted_goal_policy.hpp"
#include "rlrun/rng.hpp"
#include "runtime/cli_runner.hpp"
#include "test_paths.hpp"

using namespace rlrun;
using namespace rlrun::testing;

TEST_CASE("bench: GripperLift-v0 env steps/s and SAC training steps/s", "[.bench][gripper_bench]") {
  std::printf("| run | steps/s |\n|---|---|\n");
  for (const bool easy : {false, true}) {
    GripperLift env(GripperLift::Config{}, easy);
    std::vector<float> obs(GripperLift::kObsSize);
    Rng actions(1);
    constexpr int kSteps = 20000;  // 400 episodes: resets (a new world each) included
    const auto start = std::chrono::steady_clock::now();
    env.reset(1, obs);
    for (int i = 0; i < kSteps; ++i) {
      float a[4];
      env.action_space().sample(actions, a);
      if (env.step(a, obs).truncated) env.reset(std::nullopt, obs);
    }
    const double s =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    std::printf("| %s, random actions, one core | %.0f |\n", env.id().c_str(), kSteps / s);
  }
  // SAC as configs/grasp_sac.yaml trains it (256x256, batch 256, one update per step), 6 000
  // steps after 1 000 random ones: the update dominates.
  for (const int threads : {1, 2}) {
    TempDir dir("gripper_bench");
    const auto r = run_rlrun("--threads " + std::to_string(threads) + " train " +
                             std::string(RLRUN_SOURCE_DIR) + "/configs/grasp_sac.yaml" +
                             " --timesteps 7000 --set eval.freq=1000000 --out " + dir.str());
    std::smatch m;
    static const std::regex rate(R"(trained \d+ steps in ([0-9.]+) s \((\d+) steps/s\))");
    REQUIRE(std::regex_search(r.output, m, rate));
    std::printf("| SAC training on GripperLift-v0 (grasp_sac.yaml), %d thread%s | %s |\n", threads,
                threads > 1 ? "s" : "", m[2].str().c_str());
  }
}

// The goal tasks (GripperReach-v0, GripperPush-v0, GripperPickAndPlace-v0), same requirement:
// random actions (resets included) and the scripted controllers (episodes end on success, so
// more resets). CPU time of this process, so other work on the machine does not count.
TEST_CASE("bench: goal tasks' env steps/s", "[.bench][gripper_bench]") {
  for (const GoalTask task : {GoalTask::kReach, GoalTask::kPush, GoalTask::kPickAndPlace}) {
    for (const bool scripted : {false, true}) {
      GripperGoalEnv env(task, GripperGoalEnv::Config{});
      std::vector<float> obs(env.observation_space().flat_dim());
      Rng actions(1);
      constexpr int kSteps = 20000;
      const std::clock_t start = std::clock();
      env.reset(1, obs);
      for (int i = 0; i < kSteps; ++i) {
        float a[4];
        if (scripted) {
          const auto s = scripted_goal_action(env);
          std::copy(s.begin(), s.end(), a);
        } else {
          env.action_space().sample(actions, a);
        }
        const StepResult r =
            env.step(std::span<const float>(a, env.action_space().flat_dim()), obs);
        if (r.terminated || r.truncated) env.reset(std::nullopt, obs);
      }
      const double s = static_cast<double>(std::clock() - start) / CLOCKS_PER_SEC;
      std::printf("| %s, %s, one core (CPU time) | %.0f |\n", env.id().c_str(),
                  scripted ? "scripted controller" : "random actions", kSteps / s);
    }
  }
}
