#include "rlrun/core/regular_file.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>

#include "rlrun/core/checked_file.hpp"
#include "rlrun/core/errors.hpp"

namespace rlrun {

namespace {

// What a non-regular file is, for the refusal.
const char* kind_of(mode_t mode) {
  if (S_ISLNK(mode)) return "a symbolic link";
  if (S_ISDIR(mode)) return "a directory";
  if (S_ISFIFO(mode)) return "a FIFO (named pipe)";
  if (S_ISCHR(mode)) return "a character device";
  if (S_ISBLK(mode)) return "a block device";
  if (S_ISSOCK(mode)) return "a socket";
  return "not a regular file";
}

[[noreturn]] void refuse_kind(const std::string& shown, mode_t mode) {
  if (S_ISLNK(mode))
    throw RuntimeFailure(shown +
                         " is a symbolic link: rlrun does not follow links inside run "
                         "directories and studies (they may come from anyone; "
                         "docs/security.md)");
  throw RuntimeFailure(shown + " is " + kind_of(mode) +
                       ", not a regular file: rlrun reads and writes only regular files inside run "
                       "directories and studies (docs/security.md)");
}

// Why open(2) failed: a link, a FIFO without a reader (ENXIO) or a directory is named as such.
[[noreturn]] void refuse_open(int dirfd, const std::string& name, int error,
                              const std::string& shown, bool writing) {
  struct stat st {};
  if ((error == ELOOP || error == ENXIO || error == EISDIR || error == ENODEV) &&
      ::fstatat(dirfd, name.c_str(), &st, AT_SYMLINK_NOFOLLOW) == 0 && !S_ISREG(st.st_mode))
    refuse_kind(shown, st.st_mode);
  throw RuntimeFailure(std::string(writing ? "cannot write " : "cannot read ") + shown + ": " +
                       describe_errno(error));
}

}  // namespace

FileDescriptor open_regular_file(int dirfd, const std::string& name, int flags,
                                 const std::string& shown) {
  const bool truncate = (flags & O_TRUNC) != 0;
  const bool writing = (flags & O_ACCMODE) != O_RDONLY;
  const int safe = (flags & ~O_TRUNC) | O_NOFOLLOW | O_NONBLOCK | O_CLOEXEC | O_NOCTTY;
  FileDescriptor fd(::openat(dirfd, name.c_str(), safe, 0666));
  if (!fd) {
    if (errno == ENOENT && !(flags & O_CREAT)) return fd;
    refuse_open(dirfd, name, errno, shown, writing);
  }
  struct stat st {};
  if (::fstat(fd.get(), &st) != 0)
    throw RuntimeFailure("cannot read " + shown + ": " + describe_errno(errno));
  if (!S_ISREG(st.st_mode)) refuse_kind(shown, st.st_mode);
  // Regular: blocking I/O as usual from here on (O_NONBLOCK only kept the open from waiting).
  ::fcntl(fd.get(), F_SETFL, ::fcntl(fd.get(), F_GETFL) & ~O_NONBLOCK);
  if (truncate && ::ftruncate(fd.get(), 0) != 0)
    throw RuntimeFailure("cannot write " + shown + ": " + describe_errno(errno));
  return fd;
}

std::string describe_bytes(uint64_t bytes) {
  if (bytes >= (uint64_t{1} << 30) && bytes % (uint64_t{1} << 30) == 0)
    return std::to_string(bytes >> 30) + " GiB";
  if (bytes >= (uint64_t{1} << 20) && bytes % (uint64_t{1} << 20) == 0)
    return std::to_string(bytes >> 20) + " MiB";
  if (bytes >= 1024 && bytes % 1024 == 0) return std::to_string(bytes >> 10) + " KiB";
  return std::to_string(bytes) + (bytes == 1 ? " byte" : " bytes");
}

void refuse_oversized(const std::string& shown, uint64_t max_bytes) {
  throw RuntimeFailure(shown + " is larger than " + describe_bytes(max_bytes) +
                       ", the most rlrun reads of it (docs/security.md, \"Bounds\")");
}

std::string read_bounded(int fd, uint64_t max_bytes, const std::string& shown) {
  std::string text;
  struct stat st {};
  if (::fstat(fd, &st) == 0 && st.st_size > 0)  // a hint only: the file may grow meanwhile
    text.reserve(
        static_cast<size_t>(std::min<uint64_t>(static_cast<uint64_t>(st.st_size), max_bytes) + 1));
  char buffer[1 << 16];
  for (;;) {
    const ssize_t n = ::read(fd, buffer, sizeof buffer);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) throw RuntimeFailure("cannot read " + shown + ": " + describe_errno(errno));
    if (n == 0) return text;
    if (text.size() + static_cast<size_t>(n) > max_bytes) refuse_oversized(shown, max_bytes);
    text.append(buffer, static_cast<size_t>(n));
  }
}

}  // namespace rlrun
