#include "rlrun/core/private_temp_dir.hpp"

#include <fcntl.h>
#include <signal.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <charconv>
#include <cstring>
#include <filesystem>
#include <mutex>
#include <set>
#include <stdexcept>

#include "rlrun/core/errors.hpp"

namespace rlrun {

namespace {

namespace fs = std::filesystem;

// Removes <base>/<prefix><pid>-XXXXXX directories owned by this user whose process is gone.
// Only real directories (lstat: no symlink) of our own uid, which no one else could have
// written into (mode 0700); remove_all does not follow symlinks inside them.
void remove_stale(const fs::path& base, const std::string& prefix) {
  std::error_code ec;
  for (const auto& entry : fs::directory_iterator(base, ec)) {
    const std::string name = entry.path().filename().string();
    if (name.rfind(prefix, 0) != 0) continue;
    const size_t dash = name.find('-', prefix.size());
    if (dash == std::string::npos || dash == prefix.size()) continue;
    pid_t pid = 0;
    const auto [end, error] = std::from_chars(name.data() + prefix.size(), name.data() + dash, pid);
    if (error != std::errc() || end != name.data() + dash || pid <= 0 || pid == ::getpid())
      continue;
    struct stat st {};
    if (::lstat(entry.path().c_str(), &st) != 0 || !S_ISDIR(st.st_mode) || st.st_uid != ::geteuid())
      continue;
    if (::kill(pid, 0) == 0 || errno != ESRCH) continue;  // alive (or not ours to ask)
    std::error_code ignored;
    fs::remove_all(entry.path(), ignored);
  }
}

}  // namespace

PrivateTempDir::PrivateTempDir(const std::string& prefix, RemoveStale stale) {
  std::error_code ec;
  fs::path base = fs::temp_directory_path(ec);  // $TMPDIR, else /tmp
  if (ec) base = "/tmp";
  if (stale == RemoveStale::kYes) {
    // Once per prefix and process: leftovers appear only when a process dies.
    static std::mutex mutex;
    static std::set<std::string> swept;
    std::lock_guard lock(mutex);
    if (swept.insert(base.string() + "/" + prefix).second) remove_stale(base, prefix);
  }
  std::string name = (base / (prefix + std::to_string(::getpid()) + "-XXXXXX")).string();
  if (::mkdtemp(name.data()) == nullptr)
    throw RuntimeFailure("cannot create a temporary directory " + name + ": " +
                         std::strerror(errno));
  path_ = name;
}

PrivateTempDir::~PrivateTempDir() {
  if (keep_ || path_.empty()) return;
  std::error_code ec;
  std::filesystem::remove_all(path_, ec);  // remove_all does not follow symlinks inside
}

std::string PrivateTempDir::file(const std::string& name) const {
  if (name.empty() || name.find('/') != std::string::npos || name == "." || name == "..")
    throw std::invalid_argument("PrivateTempDir::file: '" + name + "' is not a plain file name");
  return path_ + "/" + name;
}

int PrivateTempDir::create_file(const std::string& name) const {
  const std::string path = file(name);
  const int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0600);
  if (fd < 0) throw RuntimeFailure("cannot create " + path + ": " + std::strerror(errno));
  return fd;
}

}  // namespace rlrun
