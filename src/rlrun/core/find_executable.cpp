#include "rlrun/core/find_executable.hpp"

#include <unistd.h>

#include <cstdlib>
#include <sstream>

namespace rlrun {

std::string find_executable(const std::string& binary) {
  const auto executable = [](const std::string& path) { return access(path.c_str(), X_OK) == 0; };
  if (binary.find('/') != std::string::npos) return executable(binary) ? binary : "";
  const char* path = std::getenv("PATH");
  std::stringstream dirs(path ? path : "/usr/bin:/bin");
  for (std::string dir; std::getline(dirs, dir, ':');)
    if (!dir.empty() && executable(dir + "/" + binary)) return dir + "/" + binary;
  return "";
}

}  // namespace rlrun
