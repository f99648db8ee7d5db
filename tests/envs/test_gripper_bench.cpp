// GripperLift-v0's speed (issue 8: >= 3 000 env steps/s on one core) and SAC's training speed
// on it. Measured, not asserted (DESIGN.md §8): `build/tests/rlrun_tests "[gripper_bench]"`,
// run by scripts/bench.sh.
#include <catch2/catch.hpp>
#include <chrono>
#include <cstdio>
#include <regex>
#include <string>
#include <vector>

#include "rlrun/rng.hpp"
#include "rlrun/envs/gripper/gripper_lift.hpp"
#include "runtime/cli_runner.hpp"

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
    const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
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
