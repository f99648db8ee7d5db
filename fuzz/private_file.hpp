#pragma once
// The one file each fuzz input becomes (a model file, a study journal): in a private directory
// made on first use and removed at exit, so runs never see each other's files.
#include <stdlib.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <system_error>

namespace rlrun::fuzz {

// `<tmp>/rlrun_fuzz_<tag>_XXXXXX/<name>`, the same path for the whole process.
inline const std::string& private_file(const std::string& tag, const std::string& name) {
  // The directory's name lives in a plain array: std::string statics may already be destroyed
  // when atexit handlers run.
  static char dir[4096];
  static const std::string* path = [&] {
    const std::string pattern =
        (std::filesystem::temp_directory_path() / ("rlrun_fuzz_" + tag + "_XXXXXX")).string();
    if (pattern.size() >= sizeof(dir)) std::abort();
    std::copy(pattern.begin(), pattern.end(), dir);
    if (!mkdtemp(dir)) std::abort();
    std::atexit([] {
      std::error_code ec;
      std::filesystem::remove_all(dir, ec);
    });
    return new std::string(std::string(dir) + "/" + name);
  }();
  return *path;
}

}  // namespace rlrun::fuzz
