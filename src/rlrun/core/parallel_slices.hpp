#pragma once
// Runs one job over n slices at once: slice 0 on the calling thread, slices 1..n-1 on
// persistent threads that sleep between jobs. For work that mostly waits on other processes
// (a VecEnv of Python env workers: each thread sends its envs' actions and waits for their
// replies), so the threads block rather than spin: spinning would take the cores those
// processes need. (ForkJoin, core/fork_join.hpp, is the spinning two-way split for maths.)
#include <condition_variable>
#include <exception>
#include <functional>
#include <mutex>
#include <thread>
#include <vector>

namespace rlrun {

class ParallelSlices {
 public:
  // `slices` >= 1; 1 runs every job on the calling thread.
  explicit ParallelSlices(int slices);
  ~ParallelSlices();
  ParallelSlices(const ParallelSlices&) = delete;
  ParallelSlices& operator=(const ParallelSlices&) = delete;

  int slices() const { return static_cast<int>(threads_.size()) + 1; }

  // Calls job(s) for every slice s and returns when all are done. An exception from a slice
  // is rethrown here (the lowest slice's when several throw).
  void run(const std::function<void(int slice)>& job);

 private:
  void worker(int slice);

  std::mutex mutex_;
  std::condition_variable start_, done_;
  const std::function<void(int)>* job_ = nullptr;
  uint64_t generation_ = 0;
  int pending_ = 0;
  bool stop_ = false;
  std::vector<std::exception_ptr> errors_;
  std::vector<std::thread> threads_;
};

}  // namespace rlrun
