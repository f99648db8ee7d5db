#pragma once
// Waiting for a worker process to answer (a Python env's interpreter, rlrun-sumo-worker, SUMO's
// TraCI port) without ever blocking for good: poll(2) on its socket returns at a Ctrl-C (rlrun's
// handler interrupts it, core/interrupt.hpp) and every 100 ms, and each time the wait checks
// what it was told to watch:
//   starting   the worker has not answered its first message, so nothing can be saved yet:
//              the first Ctrl-C stops rlrun (Interrupted);
//   a reply    (reset, step, SUMO's advance) a first Ctrl-C lets the reply come, so training
//              reaches its next safe point and writes its checkpoint; a worker still silent
//              kInterruptGraceSeconds after it hangs: Interrupted, without a checkpoint;
//   always     a second Ctrl-C stops rlrun at once (Interrupted); a deadline (a Python env's
//              env.startup_timeout) passed is a RuntimeFailure with the caller's message.
#include <chrono>
#include <string>

namespace rlrun {

inline constexpr double kInterruptGraceSeconds = 5.0;

struct WorkerWait {
  std::string who;   // "python:pkg.mod:Env (Python worker pid 12)", for messages
  std::string what;  // "to start", "in step()"
  bool starting = false;
  std::chrono::steady_clock::time_point since = std::chrono::steady_clock::now();
  double timeout_seconds = 0;   // 0: none
  std::string timeout_message;  // the RuntimeFailure's text when it passes
};

// Returns once `fd` is ready for `events` (POLLIN: data or the end; POLLOUT), or has failed
// (the read or write that follows reports it). Throws Interrupted or RuntimeFailure (above).
void wait_for_worker(int fd, short events, const WorkerWait& wait);

// The same checks once, for a loop that waits otherwise (SUMO's TraCI port).
void check_worker_wait(const WorkerWait& wait);

}  // namespace rlrun
