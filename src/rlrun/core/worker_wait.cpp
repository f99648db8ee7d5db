#include "rlrun/core/worker_wait.hpp"

#include <poll.h>

#include <cerrno>

#include "rlrun/core/errors.hpp"
#include "rlrun/core/interrupt.hpp"

namespace rlrun {

void check_worker_wait(const WorkerWait& wait) {
  using clock = std::chrono::steady_clock;
  const int count = interrupt_count();
  if (count >= 2)
    throw Interrupted("stopped (a second " + interrupt_name() + ") while waiting for " + wait.who +
                          " " + wait.what,
                      interrupt_signal());
  if (count == 1) {
    if (wait.starting)
      throw Interrupted(
          "stopped (" + interrupt_name() + ") while waiting for " + wait.who + " " + wait.what,
          interrupt_signal());
    const clock::time_point from = std::max(wait.since, interrupt_time());
    if (clock::now() - from > std::chrono::duration<double>(kInterruptGraceSeconds))
      throw Interrupted(wait.who + " has not answered " + wait.what + " " +
                            std::to_string(static_cast<int>(kInterruptGraceSeconds)) + " s after " +
                            interrupt_name() +
                            ": it hangs, so rlrun stopped without reaching a "
                            "safe point (no checkpoint was written)",
                        interrupt_signal());
  }
  if (wait.timeout_seconds > 0 &&
      clock::now() - wait.since > std::chrono::duration<double>(wait.timeout_seconds))
    throw RuntimeFailure(wait.timeout_message);
}

void wait_for_worker(int fd, short events, const WorkerWait& wait) {
  while (true) {
    check_worker_wait(wait);
    pollfd p{fd, events, 0};
    const int n = poll(&p, 1, 100);
    if (n > 0 || (n < 0 && errno != EINTR)) return;
  }
}

}  // namespace rlrun
