// count_of (core/plural.hpp), which every message that counts something goes through.
#include <catch2/catch.hpp>

#include "rlrun/core/plural.hpp"

using rlrun::count_of;

TEST_CASE("count_of: 1 env, 2 envs", "[plural]") {
  CHECK(count_of(1, "env") == "1 env");
  CHECK(count_of(0, "episode") == "0 episodes");
  CHECK(count_of(4, "run") == "4 runs");
  CHECK(count_of(1, "entry", "entries") == "1 entry");
  CHECK(count_of(3, "entry", "entries") == "3 entries");
}
