#pragma once
// How rlrun's hand-offs between threads wait (core/thread_pool.cpp): spin
// kSpinIterations times (about 20-50 µs; a job is ~100 µs, a futex wake-up ~10 µs), then sleep
// on std::atomic::wait.
#include <thread>

namespace rlrun {

inline constexpr int kSpinIterations = 4000;

// Pause for the first spins, then give the core away: if the thread waited for is not running,
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

}  // namespace rlrun
