#include "rlrun/core/find_executable.hpp"

#include <sys/stat.h>
#include <unistd.h>

#include <cstdlib>
#include <sstream>

namespace rlrun {

std::string find_executable(const std::string& binary) {
  // A regular file this process may execute (a directory passes access(X_OK) but not exec).
  const auto executable = [](const std::string& path) {
    struct stat st;
    return stat(path.c_str(), &st) == 0 && S_ISREG(st.st_mode) && access(path.c_str(), X_OK) == 0;
  };
  if (binary.find('/') != std::string::npos) return executable(binary) ? binary : "";
  const char* path = std::getenv("PATH");
  std::stringstream dirs(path ? path : "/usr/bin:/bin");
  for (std::string dir; std::getline(dirs, dir, ':');)
    if (!dir.empty() && executable(dir + "/" + binary)) return dir + "/" + binary;
  return "";
}

}  // namespace rlrun
