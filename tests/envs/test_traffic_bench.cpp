// TrafficSignal-v0's speed (issue 7: over traci at least 70 % of plain sumo's simulated
// seconds per second; anchors.md: plain sumo 8 372 sim steps/s, sumo-rl over traci 709).
// Measured, not asserted (docs/benchmarks.md): `build/tests/rlrun_tests "[traffic_bench]"`, run by
// scripts/bench.sh. One hour of the shipped scenario (3600 simulated seconds) each way, best
// of three, startup included:
//   plain    `sumo -c single.sumocfg --end 3600` running a fixed-time program with the same
//            plan as the env's cycle below (27 s green + 3 s yellow per approach: traffic, and
//            so SUMO's work, depends on the plan)
//   traci    the env with a fixed 30 s cycle (720 decisions of 5 s), SUMO over its socket
//   libsumo  the same with SUMO in-process
#include <catch2/catch.hpp>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "rlrun/envs/sumo/network_scenario.hpp"
#include "rlrun/envs/traffic/traffic_signal.hpp"

namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

// Wall seconds of one episode of 3600 simulated seconds as training sees it: reset (SUMO's
// start) to the last step (SUMO's end and its tripinfo read); counts the decisions.
double env_episode(rlrun::TrafficSignal& env, int& decisions) {
  const auto start = Clock::now();
  std::vector<float> obs(10);
  env.reset(1, obs);
  decisions = 0;
  rlrun::StepResult r;
  do {
    const float action = static_cast<float>((decisions / 6) % 4);  // 30 s greens
    r = env.step({&action, 1}, obs);
    ++decisions;
  } while (!r.truncated);
  return seconds_since(start);
}

double best_of_3(auto&& run) {
  double best = 1e30;
  for (int i = 0; i < 3; ++i) best = std::min(best, run());
  return best;
}

}  // namespace

TEST_CASE("bench: TrafficSignal-v0 over traci and libsumo vs plain sumo",
          "[.bench][traffic_bench]") {
  const std::string cfg =
      rlrun::traffic::load_network_scenario("scenarios/single_intersection.yaml").files.sumocfg;
  // The shipped plan (tls.tll.xml: 30 s green, 3 s yellow) with the env cycle's 27 s greens.
  std::ifstream shipped(std::filesystem::path(cfg).parent_path() / "tls.tll.xml");
  std::stringstream text;
  text << shipped.rdbuf();
  const std::string plan =
      (std::filesystem::temp_directory_path() / "rlrun_bench_tls.xml").string();
  std::ofstream(plan) << std::regex_replace(text.str(), std::regex("duration=\"30\""),
                                            "duration=\"27\"");
  const std::string plain_command = "sumo -c " + cfg + " --additional-files " + plan +
                                    " --end 3600 --no-step-log true --no-warnings true "
                                    "--duration-log.disable true >/dev/null 2>&1";
  const double plain = best_of_3([&] {
    const auto start = Clock::now();
    REQUIRE(std::system(plain_command.c_str()) == 0);
    return seconds_since(start);
  });
  std::printf("| run | decisions/s | simulated s/s | of plain sumo |\n|---|---|---|---|\n");
  std::printf("| plain `sumo`, no TraCI, fixed-time program | — | %.0f | 100 %% |\n", 3600 / plain);
  for (const char* backend : {"traci", "libsumo"})
    for (const char* reward_fn : {"queue", "diff-waiting-time"}) {
      rlrun::TrafficSignal::Config config;
      config.backend = backend;
      config.reward_fn = reward_fn;
      config.num_seconds = 3600;
      rlrun::TrafficSignal env(config);
      int decisions = 0;
      const double wall = best_of_3([&] { return env_episode(env, decisions); });
      std::printf("| env, backend %s, reward %s | %.0f | %.0f | %.0f %% |\n", backend, reward_fn,
                  decisions / wall, 3600 / wall, 100 * plain / wall);
    }
}
