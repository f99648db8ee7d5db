#include "rlrun/runtime/run_directory.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <filesystem>

#include "rlrun/core/checked_file.hpp"
#include "rlrun/core/errors.hpp"
#include "rlrun/core/temp_beside.hpp"

namespace rlrun {

namespace fs = std::filesystem;

std::string create_run_directory(const std::string& out_dir, const std::string& name, uint64_t seed) {
  const fs::path base = fs::path(out_dir) / name;
  const std::string stem = "seed" + std::to_string(seed);
  std::error_code ec;
  fs::create_directories(base, ec);
  if (ec) throw RuntimeFailure("cannot create " + base.string() + ": " + ec.message());
  // A bounded search: a path that "exists" whatever the suffix (a name the file system cuts
  // short, say) must end in an error, not spin (run names are checked when parsed).
  constexpr int kMaxAttempts = 10000;
  for (int attempt = 1; attempt <= kMaxAttempts; ++attempt) {
    const fs::path dir = base / (attempt == 1 ? stem : stem + "_" + std::to_string(attempt));
    // create_directory returns false if it already existed: try the next name.
    if (fs::create_directory(dir, ec)) return dir.string();
    if (ec) throw RuntimeFailure("cannot create " + dir.string() + ": " + ec.message());
  }
  throw RuntimeFailure("cannot create a run directory under " + base.string() + ": " + stem +
                       " to " + stem + "_" + std::to_string(kMaxAttempts) +
                       " all exist; choose another run.name or out_dir");
}

void write_text_atomic(const std::string& path, std::string_view text) {
  // A fresh temporary beside the target (O_EXCL; core/temp_beside.hpp), every write checked,
  // fsync before the rename: on a full disk the target keeps its old contents (or stays
  // absent), never a truncated file, and the temporary goes.
  // Only a regular file (or a symlink, which the rename replaces) is replaced this way: a
  // device or a FIFO named as the target must not become a regular file.
  struct stat st {};
  if (::lstat(path.c_str(), &st) == 0 && !S_ISREG(st.st_mode) && !S_ISLNK(st.st_mode))
    throw RuntimeFailure("cannot write " + path + ": not a regular file");
  const TempBeside temp = create_temp_beside(path, ".tmp");
  const auto fail = [&](int error) {
    ::close(temp.fd);
    ::unlink(temp.path.c_str());
    throw RuntimeFailure("cannot write " + path + ": " + describe_errno(error));
  };
  size_t done = 0;
  while (done < text.size()) {
    const ssize_t n = ::write(temp.fd, text.data() + done, text.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) fail(n < 0 ? errno : EIO);
    done += static_cast<size_t>(n);
  }
  if (::fsync(temp.fd) != 0) fail(errno);
  if (::close(temp.fd) != 0) {
    const int error = errno;
    ::unlink(temp.path.c_str());
    throw RuntimeFailure("cannot write " + path + ": " + describe_errno(error));
  }
  if (::rename(temp.path.c_str(), path.c_str()) != 0) {
    const int error = errno;
    ::unlink(temp.path.c_str());
    throw RuntimeFailure("cannot rename " + temp.path + " to " + path + ": " + describe_errno(error));
  }
}

}  // namespace rlrun
