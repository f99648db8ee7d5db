#pragma once
// Runs two independent pieces of work at once: one on the calling thread, one on a persistent
// worker thread (this machine kind has 2 cores). Used where an algorithm's work splits into
// independent halves — PPO/A2C's actor and critic, the two halves of an off-policy minibatch
// (nn/batch_split.hpp) — whose results do not depend on the order, so runs stay bit-identical
// with or without the worker.
// The worker spins briefly for the next job (a PPO minibatch is ~100 µs; a futex wake-up
// costs ~10 µs), then sleeps on std::atomic::wait. When the calling thread finishes its part
// before the worker has started the other one (the worker is descheduled on a busy machine, or
// still waking up), it runs that part itself: a hand-off never waits for a scheduler tick.
#include <atomic>
#include <exception>
#include <functional>
#include <thread>

namespace rlrun {

class ForkJoin {
 public:
  // `enabled` false runs both parts on the calling thread (one core, or for debugging).
  explicit ForkJoin(bool enabled = true);
  ~ForkJoin();
  ForkJoin(const ForkJoin&) = delete;
  ForkJoin& operator=(const ForkJoin&) = delete;

  // Runs `here` on this thread and `there` on the worker, or on this thread after `here` when
  // the worker has not started it by then; returns when both are done. The two must not
  // depend on which thread runs them. An exception from either is rethrown here (`there`'s
  // first).
  void run(const std::function<void()>& here, const std::function<void()>& there);

  bool enabled() const { return worker_.joinable(); }

  // The process-wide instance used by the algorithms. Its worker runs when the thread count
  // (see configure_shared) is 2.
  static ForkJoin& shared();

  // Sets the shared instance's thread count, 1 or 2, before its first use (main() calls this
  // from --threads / RLRUN_THREADS). Throws UsageError for other counts and std::logic_error
  // once shared() has been created.
  static void configure_shared(int threads);

  // The default thread count: RLRUN_THREADS when set (must be 1 or 2, else UsageError), else
  // 2 when this process may run on at least two CPUs (sched_getaffinity), else 1.
  static int default_threads();

 private:
  // kWork: a job is posted; kRunning: the worker took it; kIdle: none (or taken back).
  enum State : int { kIdle, kWork, kRunning, kDone, kStop };
  void worker_loop();
  // Spins, then sleeps, until `state` holds `value`.
  static void wait_for(std::atomic<int>& state, int value);

  std::atomic<int> state_{kIdle};
  const std::function<void()>* job_ = nullptr;
  std::exception_ptr error_;
  std::thread worker_;
};

}  // namespace rlrun
