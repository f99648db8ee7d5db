#include <catch2/catch.hpp>
#include <stdexcept>
#include <thread>

#include "rlrun/core/fork_join.hpp"

using namespace rlrun;

TEST_CASE("ForkJoin runs both parts, on two threads when enabled, and rethrows", "[core][fork_join]") {
  for (bool enabled : {true, false}) {
    ForkJoin pool(enabled);
    long a = 0, b = 0;
    std::thread::id here_id, there_id;
    for (int i = 0; i < 2000; ++i)
      pool.run([&] { ++a; here_id = std::this_thread::get_id(); },
               [&] { ++b; there_id = std::this_thread::get_id(); });
    CHECK(a == 2000);
    CHECK(b == 2000);
    CHECK(here_id == std::this_thread::get_id());
    if (pool.enabled()) CHECK(there_id != here_id);
    CHECK_THROWS_AS(pool.run([] {}, [] { throw std::runtime_error("there"); }), std::runtime_error);
    CHECK_THROWS_AS(pool.run([] { throw std::logic_error("here"); }, [] {}), std::logic_error);
    // Still usable after an exception.
    pool.run([&] { ++a; }, [&] { ++b; });
    CHECK(a + b == 4002);
  }
}
