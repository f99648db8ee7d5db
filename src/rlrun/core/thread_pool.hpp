#pragma once
// The threads a run may use: `threads - 1` persistent workers and the calling thread.
// run(parts, fn) calls fn(0), ..., fn(parts - 1), each exactly once, spread over whichever
// threads are free, and returns when all are done. Which thread runs which part must never
// change a result: callers cut their work by its size alone (nn/batch_split.hpp), each part
// writes only what it owns, and parts are combined in part order afterwards — so a run is
// bit-identical with 1, 2 or 64 threads (docs/architecture.md, "Threads").
//
// Hand-off as in EnvPool and RLtools' parallel loops: a worker spins briefly for the next job
// (a minibatch is ~100 µs; a futex wake-up ~10 µs), then sleeps on std::atomic::wait. The
// calling thread takes parts too, from the first, so a job never waits for a worker that is
// descheduled on a busy machine: the parts nobody started by the time it is free, it runs
// itself.
//
// One caller at a time: run() is not reentrant and not thread-safe (each run has one pool,
// made in main() from --threads; the Python package makes its own).
#include <atomic>
#include <cstdint>
#include <exception>
#include <thread>
#include <type_traits>
#include <vector>

namespace rlrun {

class ThreadPool {
 public:
  // threads >= 1 (std::invalid_argument otherwise); 1 runs every part on the calling thread.
  explicit ThreadPool(int threads);
  ~ThreadPool();
  ThreadPool(const ThreadPool&) = delete;
  ThreadPool& operator=(const ThreadPool&) = delete;

  int threads() const { return static_cast<int>(workers_.size()) + 1; }

  // fn(k) for k in [0, parts): see the top of this file. An exception from a part is rethrown
  // here once every part has finished (the lowest part's, when several throw). parts may be
  // at most kMaxParts.
  template <class F>
  void run(int parts, F&& fn) {
    using Fn = std::remove_reference_t<F>;
    run_job(
        parts, [](void* f, int part) { (*static_cast<Fn*>(f))(part); },
        const_cast<void*>(static_cast<const void*>(&fn)));
  }

  static constexpr int kMaxParts = 1 << 15;

 private:
  using Call = void (*)(void*, int);
  void run_job(int parts, Call call, void* fn);
  void worker_loop();
  // Claims and runs parts of the job of `generation` until none is left; false when the job
  // was not (or no longer) that generation's.
  void run_claimed_parts(uint64_t generation);
  void run_part(int part);

  // One word for the job being handed out: generation (bits 32-63), parts (16-31) and the next
  // unclaimed part (0-15), so a worker that woke for an old job can never claim a part of a
  // new one (its compare-exchange sees another generation).
  std::atomic<uint64_t> claim_{0};
  std::atomic<int> done_{0};  // parts finished of the current job
  Call call_ = nullptr;
  void* fn_ = nullptr;
  std::vector<std::exception_ptr> errors_;  // per part; grown, never shrunk
  std::atomic<bool> stop_{false};
  std::vector<std::thread> workers_;
};

}  // namespace rlrun
