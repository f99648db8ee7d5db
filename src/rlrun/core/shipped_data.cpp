#include "rlrun/core/shipped_data.hpp"

#include <algorithm>
#include <cstdint>
#include <fstream>
#include <sstream>
#include <vector>

#include "rlrun/core/errors.hpp"
#include "rlrun/core/process_settings.hpp"

namespace rlrun {

namespace fs = std::filesystem;

namespace {

// The file mapped at `address` in this process, from /proc/self/maps ("start-end perms offset
// dev inode path"). Unlike dladdr's name for a shared object (the string given to dlopen,
// possibly relative to a working directory since left), the kernel's path is absolute with
// links resolved, and it names the executable as well as any shared object.
fs::path mapped_file(std::uintptr_t address) {
  std::ifstream maps("/proc/self/maps");
  std::string line;
  while (std::getline(maps, line)) {
    std::istringstream fields(line);
    std::uintptr_t start = 0, end = 0;
    char dash = 0;
    std::string perms, offset, device, inode;
    fields >> std::hex >> start >> dash >> end >> perms >> offset >> device >> inode;
    if (!fields || dash != '-' || address < start || address >= end) continue;
    std::string path;
    std::getline(fields >> std::ws, path);
    if (!path.empty() && path.front() == '/') return path;
  }
  return {};
}

// Where to look, in the header's order; `override_set` tells whether the first is the user's.
std::vector<fs::path> candidates(bool& override_set) {
  std::vector<fs::path> out;
  const std::string& user_dir = process_settings().data_dir;  // RLRUN_DATA_DIR
  override_set = !user_dir.empty();
  if (override_set) out.emplace_back(user_dir);
  const fs::path dir = running_binary_dir();
  // RLRUN_INSTALL_DATA_FROM_BIN: CMake's relative path from the install's bin/ to its data
  // (CMAKE_INSTALL_DATADIR/rlrun; "../share/rlrun" unless changed), not a path of this machine.
  for (const fs::path& place : {dir / RLRUN_INSTALL_DATA_FROM_BIN, dir / "share" / "rlrun",
                                dir / ".." / "share" / "rlrun"}) {
    const fs::path normal = place.lexically_normal();
    if (std::find(out.begin(), out.end(), normal) == out.end()) out.push_back(normal);
  }
  return out;
}

bool holds_data(const fs::path& dir) {
  std::error_code ec;
  return fs::is_directory(dir / "scenarios", ec);
}

}  // namespace

fs::path running_binary_dir() {
  static const fs::path dir = [] {
    const fs::path file = mapped_file(reinterpret_cast<std::uintptr_t>(&mapped_file));
    if (file.empty())
      throw RuntimeFailure(
          "cannot tell where the rlrun binary is (/proc/self/maps names no file "
          "for its code); set RLRUN_DATA_DIR to rlrun's data directory");
    return file.parent_path();
  }();
  return dir;
}

std::optional<fs::path> find_shipped_data_dir() {
  bool override_set = false;
  const std::vector<fs::path> places = candidates(override_set);
  if (override_set) {
    if (holds_data(places.front())) return fs::absolute(places.front());
    throw RuntimeFailure("RLRUN_DATA_DIR=" + places.front().string() +
                         " has no scenarios/ directory: point it at rlrun's data directory "
                         "(<prefix>/share/rlrun of an install, or an rlrun checkout), or unset it");
  }
  for (const fs::path& place : places)
    if (holds_data(place)) return place;
  return std::nullopt;
}

std::string shipped_data_dir() {
  if (const auto dir = find_shipped_data_dir()) return dir->string();
  bool override_set = false;
  std::string searched;
  for (const fs::path& place : candidates(override_set)) searched += "  " + place.string() + "\n";
  throw RuntimeFailure(
      "rlrun's shipped data (configs/, scenarios/, sumo_data/) was not found. Searched, beside "
      "the rlrun binary:\n" +
      searched +
      "and RLRUN_DATA_DIR is not set. Reinstall rlrun (cmake --install puts the data in "
      "<prefix>/share/rlrun) or set RLRUN_DATA_DIR to a directory holding scenarios/");
}

std::string find_data_file(const std::string& path) {
  std::error_code ec;
  if (fs::exists(path, ec) || !fs::path(path).is_relative()) return path;
  const auto dir = find_shipped_data_dir();
  if (dir && fs::exists(*dir / path, ec)) return (*dir / path).string();
  return path;
}

}  // namespace rlrun
