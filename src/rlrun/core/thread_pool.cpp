#include "rlrun/core/thread_pool.hpp"
#include "rlrun/core/spin_wait.hpp"

#include <stdexcept>
#include <string>
#include <utility>

namespace rlrun {

namespace {

constexpr uint64_t generation_of(uint64_t claim) { return claim >> 32; }
constexpr int parts_of(uint64_t claim) { return static_cast<int>((claim >> 16) & 0xffff); }
constexpr int next_of(uint64_t claim) { return static_cast<int>(claim & 0xffff); }
constexpr uint64_t make_claim(uint64_t generation, int parts, int next) {
  return generation << 32 | static_cast<uint64_t>(parts) << 16 | static_cast<uint64_t>(next);
}

}  // namespace

ThreadPool::ThreadPool(int threads) {
  if (threads < 1)
    throw std::invalid_argument("ThreadPool: threads must be >= 1, got " + std::to_string(threads));
  workers_.reserve(static_cast<size_t>(threads - 1));
  for (int i = 1; i < threads; ++i) workers_.emplace_back([this] { worker_loop(); });
}

ThreadPool::~ThreadPool() {
  stop_.store(true, std::memory_order_release);
  // A new generation with no parts wakes every sleeping worker to see stop_.
  claim_.store(make_claim(generation_of(claim_.load()) + 1, 0, 0), std::memory_order_release);
  claim_.notify_all();
  for (std::thread& t : workers_) t.join();
}

void ThreadPool::run_part(int part) {
  try {
    call_(fn_, part);
  } catch (...) {
    errors_[static_cast<size_t>(part)] = std::current_exception();
  }
  if (done_.fetch_add(1, std::memory_order_acq_rel) + 1 ==
      parts_of(claim_.load(std::memory_order_acquire)))
    done_.notify_one();
}

void ThreadPool::run_claimed_parts(uint64_t generation) {
  uint64_t claim = claim_.load(std::memory_order_acquire);
  while (generation_of(claim) == generation && next_of(claim) < parts_of(claim)) {
    // Success means the part was unclaimed, so its job is not done and call_/fn_ are its own.
    if (claim_.compare_exchange_weak(claim, claim + 1, std::memory_order_acq_rel,
                                     std::memory_order_acquire))
      run_part(next_of(claim));
  }
}

void ThreadPool::worker_loop() {
  // The generation of a new pool, not the one this thread finds when it first runs: on a busy
  // machine a worker may start after jobs (or the destructor's stop) were posted, and must not
  // take the latest one for old news and sleep through it.
  uint64_t seen = 0;
  while (true) {
    uint64_t claim = claim_.load(std::memory_order_acquire);
    for (int i = 0; generation_of(claim) == seen && i < kSpinIterations; ++i) {
      cpu_relax(i);
      claim = claim_.load(std::memory_order_acquire);
    }
    while (generation_of(claim) == seen) {
      claim_.wait(claim, std::memory_order_acquire);
      claim = claim_.load(std::memory_order_acquire);
    }
    if (stop_.load(std::memory_order_acquire)) return;
    seen = generation_of(claim);
    run_claimed_parts(seen);
  }
}

void ThreadPool::run_job(int parts, Call call, void* fn) {
  if (parts < 0 || parts > kMaxParts)
    throw std::invalid_argument("ThreadPool::run: parts must be in [0, " +
                                std::to_string(kMaxParts) + "], got " + std::to_string(parts));
  if (parts == 0) return;
  if (errors_.size() < static_cast<size_t>(parts)) errors_.resize(static_cast<size_t>(parts));
  if (workers_.empty() || parts == 1) {
    // No hand-off: the same calls in part order, exceptions after all parts as below.
    for (int k = 0; k < parts; ++k) {
      try {
        call(fn, k);
      } catch (...) {
        errors_[static_cast<size_t>(k)] = std::current_exception();
      }
    }
  } else {
    call_ = call;
    fn_ = fn;
    done_.store(0, std::memory_order_relaxed);
    const uint64_t generation = generation_of(claim_.load(std::memory_order_relaxed)) + 1;
    claim_.store(make_claim(generation, parts, 0), std::memory_order_release);
    // Wake no more sleeping workers than there are parts for them (the calling thread takes
    // one): on a 64-core pool a two-part minibatch must not wake 63 threads. A worker left
    // asleep simply misses this job; spinning ones see it without a wake-up.
    if (static_cast<size_t>(parts - 1) >= workers_.size()) {
      claim_.notify_all();
    } else {
      for (int k = 1; k < parts; ++k) claim_.notify_one();
    }
    run_claimed_parts(generation);
    // Every part is claimed; wait for the workers still running theirs.
    int finished = done_.load(std::memory_order_acquire);
    for (int i = 0; finished != parts && i < kSpinIterations; ++i) {
      cpu_relax(i);
      finished = done_.load(std::memory_order_acquire);
    }
    while (finished != parts) {
      done_.wait(finished, std::memory_order_acquire);
      finished = done_.load(std::memory_order_acquire);
    }
  }
  for (int k = 0; k < parts; ++k) {
    if (std::exception_ptr error = std::exchange(errors_[static_cast<size_t>(k)], nullptr)) {
      for (int rest = k + 1; rest < parts; ++rest) errors_[static_cast<size_t>(rest)] = nullptr;
      std::rethrow_exception(error);
    }
  }
}

}  // namespace rlrun
