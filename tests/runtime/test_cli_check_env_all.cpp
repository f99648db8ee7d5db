// `rlrun check-env` over every registered env, as a user runs it: each built-in env must pass
// the checker (spaces, dtypes, seeding determinism, reset/step contract, observations inside
// the space, render).
#include <catch2/catch.hpp>

#include "rlrun/runtime/builtins.hpp"
#include "runtime/cli_runner.hpp"

using namespace rlrun;
using namespace rlrun::testing;

TEST_CASE("check-env passes every registered env", "[cli][env_checker]") {
  int checked = 0;
  for (const EnvEntry& entry : builtin_registry().envs()) {
    const auto r = run_rlrun("check-env " + entry.id);
    INFO(entry.id << "\n" << r.output);
    CHECK(r.exit_code == 0);
    ++checked;
  }
  CHECK(checked >= 7);  // the 5 classic-control tasks, Grasp2D-v0, GridWorld-v0
}
