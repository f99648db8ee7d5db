#pragma once
// What a process decides once, in main() (apps/rlrun/main.cpp) or in the Python module, and
// hands down to every run it starts, rather than each layer reading the environment or a
// process-wide instance: the threads a run may use (`--threads N|auto`). Layers below take
// what they need from it (AlgorithmSetup::pool, VecEnv::set_thread_pool).
#include "rlrun/core/thread_pool.hpp"

namespace rlrun {

struct ExecutionContext {
  ThreadPool* pool = nullptr;  // null: everything on the calling thread

  int threads() const { return pool ? pool->threads() : 1; }
};

}  // namespace rlrun
