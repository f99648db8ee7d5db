#pragma once
// One training process per run directory: an exclusive flock(2) on `<run_dir>/.lock`, held
// while the run trains (a new run, `train --resume`, or `sweep run`). A second process that
// resumes the same run at the same time would append the same rows twice and race on the
// checkpoints; it is refused instead, naming the process that holds the run. The kernel drops
// the lock when the holder exits, even when killed, so a stale lock file never blocks a resume.
#include <string>

namespace rlrun {

class DirHandle;  // core/dir_handle.hpp

class RunLock {
 public:
  // Throws RuntimeFailure when another process holds the run, or the lock cannot be made
  // (`.lock` is opened in the run directory without following a link, and must be regular).
  explicit RunLock(const DirHandle& run_dir);
  ~RunLock();
  RunLock(const RunLock&) = delete;
  RunLock& operator=(const RunLock&) = delete;

 private:
  int fd_ = -1;
};

}  // namespace rlrun
