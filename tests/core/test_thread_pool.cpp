#include <sched.h>

#include <atomic>
#include <catch2/catch.hpp>
#include <chrono>
#include <mutex>
#include <set>
#include <stdexcept>
#include <thread>
#include <vector>

#include "rlrun/core/available_cpus.hpp"
#include "rlrun/core/thread_pool.hpp"

using namespace rlrun;

TEST_CASE("ThreadPool runs every part exactly once, for any thread and part count",
          "[core][thread_pool]") {
  for (int threads : {1, 2, 3, 8}) {
    ThreadPool pool(threads);
    CHECK(pool.threads() == threads);
    for (int parts : {0, 1, 2, 3, 7, 64, 1000}) {
      std::vector<std::atomic<int>> runs(static_cast<size_t>(parts));
      for (int round = 0; round < (parts > 64 ? 20 : 300); ++round)
        pool.run(parts, [&](int k) { runs[static_cast<size_t>(k)].fetch_add(1); });
      for (int k = 0; k < parts; ++k) {
        INFO("threads " << threads << ", parts " << parts << ", part " << k);
        CHECK(runs[static_cast<size_t>(k)].load() == (parts > 64 ? 20 : 300));
      }
    }
  }
}

TEST_CASE("ThreadPool: parts combined in part order give the same bits with any thread count",
          "[core][thread_pool]") {
  std::vector<float> values(100000);
  for (size_t i = 0; i < values.size(); ++i) values[i] = 1.0f / static_cast<float>(i + 1);
  auto sum_with = [&](int threads) {
    ThreadPool pool(threads);
    constexpr int kParts = 7;
    std::vector<float> partial(kParts, 0.0f);
    pool.run(kParts, [&](int k) {
      const size_t begin = values.size() * static_cast<size_t>(k) / kParts;
      const size_t end = values.size() * static_cast<size_t>(k + 1) / kParts;
      for (size_t i = begin; i < end; ++i) partial[static_cast<size_t>(k)] += values[i];
    });
    float total = 0.0f;
    for (float p : partial) total += p;
    return total;
  };
  const float one = sum_with(1);
  for (int threads : {2, 3, 8}) CHECK(sum_with(threads) == one);
}

TEST_CASE("ThreadPool spreads parts over its threads", "[core][thread_pool]") {
  ThreadPool pool(3);
  std::mutex mutex;
  std::set<std::thread::id> ids;
  std::atomic<int> arrived{0};
  // Each part waits until all three have started (or 10 s), so three threads must take them.
  pool.run(3, [&](int) {
    {
      std::lock_guard lock(mutex);
      ids.insert(std::this_thread::get_id());
    }
    arrived.fetch_add(1);
    const auto give_up = std::chrono::steady_clock::now() + std::chrono::seconds(10);
    while (arrived.load() < 3 && std::chrono::steady_clock::now() < give_up)
      std::this_thread::yield();
  });
  CHECK(ids.size() == 3);
  CHECK(ids.count(std::this_thread::get_id()) == 1);
}

TEST_CASE("ThreadPool rethrows the lowest failing part's exception after all parts ran",
          "[core][thread_pool]") {
  for (int threads : {1, 4}) {
    ThreadPool pool(threads);
    std::atomic<int> ran{0};
    try {
      pool.run(6, [&](int k) {
        ran.fetch_add(1);
        if (k == 4) throw std::runtime_error("part 4");
        if (k == 2) throw std::runtime_error("part 2");
      });
      FAIL("no exception");
    } catch (const std::runtime_error& e) {
      CHECK(std::string(e.what()) == "part 2");
    }
    CHECK(ran.load() == 6);
    int after = 0;
    pool.run(1, [&](int) { ++after; });  // still usable, and the old errors are gone
    CHECK(after == 1);
  }
  CHECK_THROWS_AS(ThreadPool(0), std::invalid_argument);
  ThreadPool pool(2);
  CHECK_THROWS_AS(pool.run(-1, [](int) {}), std::invalid_argument);
}

TEST_CASE("available_cpus: the affinity mask and the cgroup quota, whichever is smaller",
          "[core][thread_pool]") {
  CHECK_FALSE(cpus_of_cgroup_v2_max("max 100000\n"));
  CHECK(cpus_of_cgroup_v2_max("200000 100000\n") == 2);
  CHECK(cpus_of_cgroup_v2_max("150000 100000") == 2);  // 1.5 CPUs: two threads may run
  CHECK(cpus_of_cgroup_v2_max("50000 100000") == 1);
  CHECK_FALSE(cpus_of_cgroup_v2_max(""));
  CHECK_FALSE(cpus_of_cgroup_v2_max("garbage"));
  CHECK_FALSE(cpus_of_cgroup_v1("-1\n", "100000\n"));
  CHECK(cpus_of_cgroup_v1("250000\n", "100000\n") == 3);
  CHECK_FALSE(cpus_of_cgroup_v1("", ""));

  const int all = available_cpus();
  CHECK(all >= 1);
  CHECK(all <= static_cast<int>(std::max(1u, std::thread::hardware_concurrency())));
  // Pinned to one CPU (as `taskset -c 0` would), this thread may use one.
  cpu_set_t before, one;
  REQUIRE(sched_getaffinity(0, sizeof(before), &before) == 0);
  CPU_ZERO(&one);
  for (int cpu = 0; cpu < CPU_SETSIZE; ++cpu)
    if (CPU_ISSET(cpu, &before)) {
      CPU_SET(cpu, &one);
      break;
    }
  REQUIRE(sched_setaffinity(0, sizeof(one), &one) == 0);
  const int pinned = available_cpus();
  REQUIRE(sched_setaffinity(0, sizeof(before), &before) == 0);
  CHECK(pinned == 1);
}
