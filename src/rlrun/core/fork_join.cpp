#include "rlrun/core/fork_join.hpp"

#include <sched.h>

#include <cstdlib>
#include <stdexcept>
#include <string>

#include "rlrun/core/errors.hpp"
#include "rlrun/core/spin_wait.hpp"

namespace rlrun {

ForkJoin::ForkJoin(bool enabled) {
  if (enabled && std::thread::hardware_concurrency() > 1) worker_ = std::thread([this] { worker_loop(); });
}

ForkJoin::~ForkJoin() {
  if (!worker_.joinable()) return;
  state_.store(kStop, std::memory_order_release);
  state_.notify_one();
  worker_.join();
}

namespace {
// 0 = not configured yet; set by configure_shared before the first shared().
int g_shared_threads = 0;
bool g_shared_created = false;

int checked_thread_count(int threads, const std::string& source) {
  if (threads != 1 && threads != 2)
    throw UsageError(source + " must be 1 or 2 (a run uses at most two cores), got " +
                     std::to_string(threads));
  return threads;
}
}  // namespace

int ForkJoin::default_threads() {
  if (const char* env = std::getenv("RLRUN_THREADS"); env && *env) {
    char* end = nullptr;
    const long value = std::strtol(env, &end, 10);
    if (*end != '\0') throw UsageError(std::string("RLRUN_THREADS must be 1 or 2, got '") + env + "'");
    return checked_thread_count(static_cast<int>(value), "RLRUN_THREADS");
  }
  // On by default: on a quiet 2-core machine the second core makes PPO 1.6x and DQN/TD3 ~1.8x
  // faster (docs/benchmarks.md). Runs sharing the cores (parallel sweeps) should pass
  // --threads 1: a descheduled worker makes every hand-off wait for a scheduler tick.
  cpu_set_t cpus;
  if (sched_getaffinity(0, sizeof(cpus), &cpus) == 0) return CPU_COUNT(&cpus) >= 2 ? 2 : 1;
  return std::thread::hardware_concurrency() >= 2 ? 2 : 1;
}

void ForkJoin::configure_shared(int threads) {
  checked_thread_count(threads, "--threads");
  if (g_shared_created) throw std::logic_error("ForkJoin::configure_shared after first use");
  g_shared_threads = threads;
}

ForkJoin& ForkJoin::shared() {
  static ForkJoin instance([] {
    g_shared_created = true;
    if (g_shared_threads == 0) {
      try {
        g_shared_threads = default_threads();
      } catch (const UsageError&) {
        g_shared_threads = 1;  // main() reports a bad RLRUN_THREADS before training starts
      }
    }
    return g_shared_threads == 2;
  }());
  return instance;
}

void ForkJoin::wait_for(std::atomic<int>& state, int value) {
  for (int i = 0; i < kSpinIterations; ++i) {
    if (state.load(std::memory_order_acquire) == value) return;
    cpu_relax(i);
  }
  for (int current = state.load(std::memory_order_acquire); current != value;
       current = state.load(std::memory_order_acquire))
    state.wait(current, std::memory_order_acquire);
}

void ForkJoin::worker_loop() {
  while (true) {
    // Until kWork or kStop: after its kDone the worker must not see kDone as new work.
    int state = state_.load(std::memory_order_acquire);
    for (int i = 0; (state == kIdle || state == kDone) && i < kSpinIterations; ++i) {
      cpu_relax(i);
      state = state_.load(std::memory_order_acquire);
    }
    while (state == kIdle || state == kDone) {
      state_.wait(state, std::memory_order_acquire);
      state = state_.load(std::memory_order_acquire);
    }
    if (state == kStop) return;
    // Take the job unless the calling thread took it back meanwhile (then wait again).
    if (!state_.compare_exchange_strong(state, kRunning, std::memory_order_acq_rel)) continue;
    try {
      (*job_)();
    } catch (...) {
      error_ = std::current_exception();
    }
    state_.store(kDone, std::memory_order_release);
    state_.notify_one();
  }
}

void ForkJoin::run(const std::function<void()>& here, const std::function<void()>& there) {
  if (!worker_.joinable()) {
    here();
    there();
    return;
  }
  job_ = &there;
  error_ = nullptr;
  state_.store(kWork, std::memory_order_release);
  state_.notify_one();
  std::exception_ptr here_error;
  try {
    here();
  } catch (...) {
    here_error = std::current_exception();
  }
  int posted = kWork;
  if (state_.compare_exchange_strong(posted, kIdle, std::memory_order_acq_rel)) {
    // The worker has not started `there`: run it here rather than wait for it to be scheduled.
    try {
      there();
    } catch (...) {
      error_ = std::current_exception();
    }
  } else {
    wait_for(state_, kDone);
    state_.store(kIdle, std::memory_order_release);
  }
  if (error_) std::rethrow_exception(error_);
  if (here_error) std::rethrow_exception(here_error);
}

}  // namespace rlrun
