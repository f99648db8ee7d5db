#include "rlrun/core/parallel_slices.hpp"

#include <stdexcept>

namespace rlrun {

ParallelSlices::ParallelSlices(int slices) {
  if (slices < 1) throw std::invalid_argument("ParallelSlices: needs at least one slice");
  errors_.resize(static_cast<size_t>(slices));
  for (int s = 1; s < slices; ++s) threads_.emplace_back([this, s] { worker(s); });
}

ParallelSlices::~ParallelSlices() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stop_ = true;
  }
  start_.notify_all();
  for (std::thread& t : threads_) t.join();
}

void ParallelSlices::run(const std::function<void(int)>& job) {
  if (threads_.empty()) {
    job(0);
    return;
  }
  {
    std::lock_guard<std::mutex> lock(mutex_);
    job_ = &job;
    pending_ = static_cast<int>(threads_.size());
    ++generation_;
    for (auto& e : errors_) e = nullptr;
  }
  start_.notify_all();
  try {
    job(0);
  } catch (...) {
    errors_[0] = std::current_exception();
  }
  std::unique_lock<std::mutex> lock(mutex_);
  done_.wait(lock, [this] { return pending_ == 0; });
  job_ = nullptr;
  for (const auto& e : errors_)
    if (e) std::rethrow_exception(e);
}

void ParallelSlices::worker(int slice) {
  uint64_t seen = 0;
  while (true) {
    const std::function<void(int)>* job;
    {
      std::unique_lock<std::mutex> lock(mutex_);
      start_.wait(lock, [&] { return stop_ || generation_ != seen; });
      if (stop_) return;
      seen = generation_;
      job = job_;
    }
    std::exception_ptr error;
    try {
      (*job)(slice);
    } catch (...) {
      error = std::current_exception();
    }
    {
      std::lock_guard<std::mutex> lock(mutex_);
      errors_[static_cast<size_t>(slice)] = error;
      --pending_;
    }
    done_.notify_one();
  }
}

}  // namespace rlrun
