#pragma once
// Runs two independent pieces of work at once: one on the calling thread, one on a persistent
// worker thread (this machine kind has 2 cores). Used where an algorithm's work splits into
// independent halves — PPO/A2C's actor and critic, SAC/TD3's twin critics — whose results do
// not depend on the order, so runs stay bit-identical with or without the worker.
// The worker spins briefly for the next job (a PPO minibatch is ~100 µs; a futex wake-up
// costs ~10 µs), then sleeps on std::atomic::wait.
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

  // Runs `here` on this thread and `there` on the worker; returns when both are done.
  // An exception from either is rethrown here (the worker's first).
  void run(const std::function<void()>& here, const std::function<void()>& there);

  bool enabled() const { return worker_.joinable(); }

  // The process-wide instance; the worker runs only with RLRUN_THREADS=2 in the environment.
  static ForkJoin& shared();

 private:
  enum State : int { kIdle, kWork, kDone, kStop };
  void worker_loop();
  // Spins, then sleeps, until `state` holds `value`.
  static void wait_for(std::atomic<int>& state, int value);

  std::atomic<int> state_{kIdle};
  const std::function<void()>* job_ = nullptr;
  std::exception_ptr error_;
  std::thread worker_;
};

}  // namespace rlrun
