#include "rlrun/core/trusted_values.hpp"

#include <algorithm>
#include <filesystem>

namespace rlrun {

namespace fs = std::filesystem;

std::string shipped_data_dir() { return RLRUN_DATA_DIR; }

namespace {

// The message for a value untrusted text may not set: what it is and how to vouch for it.
[[noreturn]] void refuse(const ConfigNode& n, const std::string& what, const std::string& value) {
  n.fail(what + " '" + value + "' named in " + n.origin() +
         ", which rlrun does not trust (model files, checkpoints, run directories and sweep "
         "manifests may come from anyone; docs/security.md). If you trust it, pass --set " +
         n.path() + "=" + value + " (or another value) on the command line");
}

// The canonical path of `path` when it names an existing file inside the shipped data
// directory (a relative path counts from there, not from the working directory), else "".
std::string shipped_file(const std::string& path) {
  std::error_code ec;
  const fs::path data = fs::weakly_canonical(shipped_data_dir(), ec);
  if (ec) return "";
  const fs::path file = fs::weakly_canonical(fs::path(path).is_absolute() ? fs::path(path)
                                                                           : data / path, ec);
  if (ec || !fs::is_regular_file(file, ec)) return "";
  const auto [d, f] = std::mismatch(data.begin(), data.end(), file.begin(), file.end());
  return d == data.end() ? file.string() : "";
}

}  // namespace

void decode(const ConfigNode& n, ProgramPath& out) {
  const std::string value = n.as_string();
  if (!n.trusted() && value != out.value) refuse(n, "a program to run,", value);
  out.value = value;
}

void decode(const ConfigNode& n, OutputPath& out) {
  const std::string value = n.as_string();
  if (!n.trusted() && value != out.value) refuse(n, "an output file,", value);
  out.value = value;
}

void decode(const ConfigNode& n, SimulatorInput& out) {
  const std::string value = n.as_string();
  if (n.trusted() || value == out.value) {
    out.value = value;
    return;
  }
  out.value = shipped_file(value);
  if (out.value.empty())
    refuse(n, "a simulator input file (it can make the simulator write files),", value);
}

}  // namespace rlrun
