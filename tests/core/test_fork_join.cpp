#include <atomic>
#include <catch2/catch.hpp>
#include <chrono>
#include <cstdlib>
#include <string>
#include <stdexcept>
#include <thread>

#include "rlrun/core/errors.hpp"
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
    if (pool.enabled()) {
      // The worker runs `there` when it starts it before `here` ends (otherwise the calling
      // thread runs it after `here`, as it did for most of the short jobs above).
      std::atomic<bool> started{false};
      pool.run(
          [&] {
            const auto give_up = std::chrono::steady_clock::now() + std::chrono::seconds(10);
            while (!started.load() && std::chrono::steady_clock::now() < give_up)
              std::this_thread::yield();
          },
          [&] {
            started = true;
            there_id = std::this_thread::get_id();
          });
      CHECK(there_id != here_id);
    }
    CHECK_THROWS_AS(pool.run([] {}, [] { throw std::runtime_error("there"); }), std::runtime_error);
    CHECK_THROWS_AS(pool.run([] { throw std::logic_error("here"); }, [] {}), std::logic_error);
    // Still usable after an exception.
    pool.run([&] { ++a; }, [&] { ++b; });
    CHECK(a + b == 4002);
  }
}

TEST_CASE("The thread count comes from RLRUN_THREADS, else from the CPUs available",
          "[core][fork_join]") {
  const char* saved = std::getenv("RLRUN_THREADS");
  const std::string saved_value = saved ? saved : "";
  setenv("RLRUN_THREADS", "1", 1);
  CHECK(ForkJoin::default_threads() == 1);
  setenv("RLRUN_THREADS", "2", 1);
  CHECK(ForkJoin::default_threads() == 2);
  for (const char* bad : {"3", "0", "two", "2x"}) {
    setenv("RLRUN_THREADS", bad, 1);
    CHECK_THROWS_AS(ForkJoin::default_threads(), UsageError);
  }
  unsetenv("RLRUN_THREADS");
  const int n = ForkJoin::default_threads();
  CHECK((n == 1 || n == 2));
  if (std::thread::hardware_concurrency() == 1) CHECK(n == 1);
  CHECK_THROWS_AS(ForkJoin::configure_shared(4), UsageError);
  if (saved) setenv("RLRUN_THREADS", saved_value.c_str(), 1);
}
