#include "rlrun/core/fork_join.hpp"

#include <cstdlib>
#include <cstring>

namespace rlrun {

namespace {
// About 20-50 µs of spinning before sleeping.
constexpr int kSpinIterations = 4000;

// Pause for the first spins, then give the core away: if the other thread is not running,
// spinning only delays it.
inline void cpu_relax(int iteration) {
  if (iteration < 2000) {
#if defined(__x86_64__) || defined(__i386__)
    __builtin_ia32_pause();
#endif
  } else {
    std::this_thread::yield();
  }
}
}  // namespace

ForkJoin::ForkJoin(bool enabled) {
  if (enabled && std::thread::hardware_concurrency() > 1) worker_ = std::thread([this] { worker_loop(); });
}

ForkJoin::~ForkJoin() {
  if (!worker_.joinable()) return;
  state_.store(kStop, std::memory_order_release);
  state_.notify_one();
  worker_.join();
}

ForkJoin& ForkJoin::shared() {
  // Opt-in (RLRUN_THREADS=2): on a loaded machine a descheduled worker makes every hand-off
  // wait a scheduler tick, which costs far more than the halved work (docs/benchmarks.md).
  static ForkJoin instance([] {
    const char* threads = std::getenv("RLRUN_THREADS");
    return threads && std::strcmp(threads, "2") == 0;
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
  wait_for(state_, kDone);
  state_.store(kIdle, std::memory_order_release);
  if (error_) std::rethrow_exception(error_);
  if (here_error) std::rethrow_exception(here_error);
}

}  // namespace rlrun
