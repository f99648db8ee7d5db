#include "rlrun/runtime/io/run_lock.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

#include "rlrun/core/dir_handle.hpp"
#include "rlrun/core/errors.hpp"
#include "rlrun/core/regular_file.hpp"

namespace rlrun {

RunLock::RunLock(const DirHandle& run_dir) {
  const std::string path = run_dir.child(".lock");
  // A run directory may come from anyone: a planted link or FIFO is refused, not followed.
  fd_ = open_regular_file(run_dir.fd(), ".lock", O_RDWR | O_CREAT, path).release();
  if (flock(fd_, LOCK_EX | LOCK_NB) != 0) {
    const int error = errno;
    char holder[32] = {0};
    const ssize_t n = pread(fd_, holder, sizeof holder - 1, 0);
    close(fd_);
    fd_ = -1;
    if (error == EWOULDBLOCK)
      throw RuntimeFailure(
          "another rlrun process" +
          (n > 0 ? " (pid " + std::string(holder, strcspn(holder, "\n")) + ")" : std::string()) +
          " is training " + run_dir.path() + "; wait for it to finish or stop it first");
    throw RuntimeFailure("cannot lock " + path + ": " + std::strerror(error));
  }
  // The holder's pid, for the message above (informational only).
  const std::string pid = std::to_string(getpid()) + "\n";
  if (ftruncate(fd_, 0) == 0) {
    const ssize_t written = pwrite(fd_, pid.data(), pid.size(), 0);
    (void)written;
  }
}

RunLock::~RunLock() {
  if (fd_ >= 0) close(fd_);  // releases the lock
}

}  // namespace rlrun
