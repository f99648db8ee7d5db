#include "rlrun/core/temp_beside.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <random>

#include "rlrun/core/checked_file.hpp"
#include "rlrun/core/dir_handle.hpp"
#include "rlrun/core/errors.hpp"

namespace rlrun {

namespace {

// The process's umask without changing it (umask(2) can only be read by setting it, which
// would race with other threads creating files): Linux shows it in /proc/self/status.
mode_t current_umask() {
  std::ifstream status("/proc/self/status");
  for (std::string line; std::getline(status, line);)
    if (line.rfind("Umask:", 0) == 0)
      return static_cast<mode_t>(std::stoul(line.substr(6), nullptr, 8));
  return 022;
}

// Six characters as mkstemp's XXXXXX: letters and digits.
std::string random_letters() {
  static constexpr char kAlphabet[] =
      "abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789";
  static thread_local std::mt19937_64 rng(std::random_device{}());
  std::string text(6, 'x');
  for (char& c : text) c = kAlphabet[rng() % (sizeof kAlphabet - 1)];
  return text;
}

}  // namespace

TempBeside create_temp_beside(const std::string& target, const std::string& suffix) {
  const std::filesystem::path p(target);
  // Appended piecewise: GCC 12 warns falsely (-Wrestrict) on "." + std::string temporaries.
  std::string name = ".";
  name += p.filename().string();
  name += ".XXXXXX";
  name += suffix;
  TempBeside temp;
  temp.path = (p.parent_path() / name).string();
  temp.fd = ::mkostemps(temp.path.data(), static_cast<int>(suffix.size()), O_CLOEXEC);
  if (temp.fd < 0)
    throw RuntimeFailure("cannot create a temporary file beside " + target + ": " +
                         std::strerror(errno));
  ::fchmod(temp.fd, 0666 & ~current_umask());
  return temp;
}

TempBeside create_temp_in(const DirHandle& dir, const std::string& name,
                          const std::string& suffix) {
  // Fresh names until one is new (O_EXCL): a file or link already there is never reused.
  for (int attempt = 0; attempt < 100; ++attempt) {
    TempBeside temp;
    temp.path = ".";  // appended piecewise: GCC 12's false -Wrestrict, as above
    temp.path += name;
    temp.path += '.';
    temp.path += random_letters();
    temp.path += suffix;
    temp.fd = ::openat(dir.fd(), temp.path.c_str(),
                       O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0666);
    if (temp.fd >= 0) return temp;
    if (errno != EEXIST)
      throw RuntimeFailure("cannot create a temporary file beside " + dir.child(name) + ": " +
                           describe_errno(errno));
  }
  throw RuntimeFailure("cannot create a temporary file beside " + dir.child(name) +
                       ": 100 fresh names all exist");
}

}  // namespace rlrun
