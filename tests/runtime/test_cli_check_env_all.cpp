// `rlrun check-env` over every registered env, as a user runs it: each built-in env must pass
// the checker (spaces, dtypes, seeding determinism, reset/step contract, observations inside
// the space, render).
#include <catch2/catch.hpp>

#include "rlrun/runtime/components/builtins.hpp"
#include "runtime/cli_runner.hpp"

using namespace rlrun;
using namespace rlrun::testing;

TEST_CASE("check-env passes every registered env", "[cli][env_checker]") {
  int checked = 0;
  for (const EnvEntry& entry : builtin_registry().envs()) {
    if (entry.expand) continue;  // id families (python:, gymnasium:): tests/envs/test_python_env*
    // The SUMO envs simulate an hour per episode by default: shorter episodes keep this quick.
    const bool sumo = entry.id == "TrafficSignal-v0" || entry.id == "TrafficNetwork-v0";
    const std::string shorter = sumo ? " --set num_seconds=300 --episodes 3 --steps 200" : "";
    const auto r = run_rlrun("check-env " + entry.id + shorter);
    INFO(entry.id << "\n" << r.output);
    CHECK(r.exit_code == 0);
    ++checked;
  }
  CHECK(checked >= 8);  // 5 classic-control tasks, Grasp2D-v0, GridWorld-v0, TrafficSignal-v0
}
