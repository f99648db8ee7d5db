#include "rlrun/core/temp_beside.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>

#include "rlrun/core/errors.hpp"

namespace rlrun {

namespace {

// The process's umask without changing it (umask(2) can only be read by setting it, which
// would race with other threads creating files): Linux shows it in /proc/self/status.
mode_t current_umask() {
  std::ifstream status("/proc/self/status");
  for (std::string line; std::getline(status, line);)
    if (line.rfind("Umask:", 0) == 0) return static_cast<mode_t>(std::stoul(line.substr(6), nullptr, 8));
  return 022;
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

}  // namespace rlrun
