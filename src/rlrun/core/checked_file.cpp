#include "rlrun/core/checked_file.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <utility>

#include "rlrun/core/errors.hpp"
#include "rlrun/core/regular_file.hpp"

namespace rlrun {

std::string describe_errno(int error) {
  std::string text = std::strerror(error);
  // glibc >= 2.32 names the constant; it is what people search for.
  if (const char* name = strerrorname_np(error)) text += std::string(" (") + name + ")";
  return text;
}

void check_writable_file(const std::string& path) {
  const std::filesystem::path parent = std::filesystem::path(path).parent_path();
  std::error_code ec;
  if (!parent.empty()) std::filesystem::create_directories(parent, ec);  // as write_csv does
  struct stat st {};
  const bool exists = ::stat(path.c_str(), &st) == 0;
  if (exists && S_ISDIR(st.st_mode))
    throw RuntimeFailure("cannot write " + path + ": it is a directory");
  if (exists && !S_ISREG(st.st_mode)) return;
  const int fd = ::open(path.c_str(), O_WRONLY | O_CLOEXEC | (exists ? 0 : O_CREAT | O_EXCL), 0666);
  if (fd < 0) throw RuntimeFailure("cannot write " + path + ": " + describe_errno(errno));
  ::close(fd);
  if (!exists) ::unlink(path.c_str());
}

CheckedFile::CheckedFile(std::string path, Mode mode) : path_(std::move(path)) {
  const int flags = O_WRONLY | O_CREAT | O_CLOEXEC | (mode == Mode::kAppend ? O_APPEND : O_TRUNC);
  fd_ = ::open(path_.c_str(), flags, 0666);
  if (fd_ < 0) throw RuntimeFailure("cannot write " + path_ + ": " + describe_errno(errno));
}

CheckedFile CheckedFile::run_file(std::string path, Mode mode) {
  const int flags = O_WRONLY | O_CREAT | (mode == Mode::kAppend ? O_APPEND : O_TRUNC);
  FileDescriptor fd = open_regular_file(AT_FDCWD, path, flags, path);
  return adopt(std::move(fd), std::move(path));
}

CheckedFile CheckedFile::adopt(FileDescriptor fd, std::string path) {
  CheckedFile file;
  file.path_ = std::move(path);
  file.fd_ = fd.release();
  return file;
}

CheckedFile::~CheckedFile() {
  if (fd_ < 0) return;
  try {
    flush();
  } catch (const std::exception&) {
    // Reported by the flush() that failed first, or unreportable here.
  }
  release();
}

CheckedFile::CheckedFile(CheckedFile&& other) noexcept
    : path_(std::move(other.path_)),
      fd_(std::exchange(other.fd_, -1)),
      buffer_(std::move(other.buffer_)) {}

CheckedFile& CheckedFile::operator=(CheckedFile&& other) noexcept {
  if (this != &other) {
    release();
    path_ = std::move(other.path_);
    fd_ = std::exchange(other.fd_, -1);
    buffer_ = std::move(other.buffer_);
  }
  return *this;
}

void CheckedFile::flush() {
  if (fd_ < 0 || buffer_.empty()) return;
  size_t done = 0;
  while (done < buffer_.size()) {
    const ssize_t n = ::write(fd_, buffer_.data() + done, buffer_.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) {
      // A short write is retried above; this is the call that says why it stopped.
      const int error = n < 0 ? errno : EIO;
      buffer_.erase(0, done);
      throw RuntimeFailure("cannot write " + path_ + ": " + describe_errno(error));
    }
    done += static_cast<size_t>(n);
  }
  buffer_.clear();  // keeps its capacity: no allocation for the next rows
}

void CheckedFile::close() {
  if (fd_ < 0) return;
  flush();
  const int fd = std::exchange(fd_, -1);
  if (::close(fd) != 0)
    throw RuntimeFailure("cannot write " + path_ + ": " + describe_errno(errno));
}

void CheckedFile::release() noexcept {
  if (fd_ >= 0) ::close(fd_);
  fd_ = -1;
  buffer_.clear();
}

}  // namespace rlrun
