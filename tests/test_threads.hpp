#pragma once
// The threads tests and micro-benchmarks run training on: RLRUN_THREADS when set (as
// `RLRUN_THREADS=1 build/tests/rlrun_tests "[dqn_bench]"` in docs/benchmarks.md), else the CPUs
// this process may use. No result may depend on it (tests/runtime/test_cli_threads.cpp).
#include <algorithm>
#include <cstdlib>
#include <string>

#include "rlrun/core/available_cpus.hpp"
#include "rlrun/core/execution_context.hpp"
#include "rlrun/core/thread_pool.hpp"

namespace rlrun::testing {

inline ThreadPool& test_thread_pool() {
  static ThreadPool pool([] {
    const char* env = std::getenv("RLRUN_THREADS");
    return env != nullptr && *env != '\0' ? std::max(1, std::atoi(env)) : available_cpus();
  }());
  return pool;
}

inline ExecutionContext test_execution() { return ExecutionContext{&test_thread_pool()}; }

}  // namespace rlrun::testing
