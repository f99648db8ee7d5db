#include "rlrun/core/private_temp_dir.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <stdexcept>

#include "rlrun/core/errors.hpp"

namespace rlrun {

PrivateTempDir::PrivateTempDir(const std::string& prefix) {
  std::error_code ec;
  std::filesystem::path base = std::filesystem::temp_directory_path(ec);  // $TMPDIR, else /tmp
  if (ec) base = "/tmp";
  std::string name = (base / (prefix + "XXXXXX")).string();
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
