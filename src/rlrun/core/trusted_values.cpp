#include "rlrun/core/trusted_values.hpp"

#include <algorithm>
#include <filesystem>
#include <vector>

#include "rlrun/core/shipped_data.hpp"

namespace rlrun {

namespace fs = std::filesystem;

namespace {

// The message for a value untrusted text may not set: what it is and how to vouch for it.
[[noreturn]] void refuse(const ConfigNode& n, const std::string& what, const std::string& value) {
  n.fail(what + " '" + value + "' named in " + n.origin() +
         ", which rlrun does not trust (model files, checkpoints, run directories, sweep "
         "manifests and zoo files may come from anyone; docs/security.md). If you trust it, pass --set " +
         n.path() + "=" + value + " (or another value) on the command line");
}

// The directories untrusted text may name files in: the shipped data directory and each
// directory directly in it, all canonical. The second matters where the data directory holds
// links (a build tree's build/share/rlrun/scenarios -> <source>/scenarios): a file reached
// through one canonicalises to the link's target, outside the data directory's own path.
std::vector<fs::path> shipped_roots() {
  std::error_code ec;
  const auto found = find_shipped_data_dir();
  if (!found) return {};
  const fs::path data = fs::canonical(*found, ec);
  if (ec) return {};
  std::vector<fs::path> roots{data};
  for (const fs::directory_entry& entry : fs::directory_iterator(data, ec))
    if (entry.is_directory(ec)) roots.push_back(fs::canonical(entry.path(), ec));
  return roots;
}

bool inside(const fs::path& dir, const fs::path& file) {
  return std::mismatch(dir.begin(), dir.end(), file.begin(), file.end()).first == dir.end();
}

// The canonical path of `path` when it names an existing file inside the shipped data
// directory (a relative path counts from there, not from the working directory), else "".
std::string shipped_file(const std::string& path) {
  const std::vector<fs::path> roots = shipped_roots();
  if (roots.empty()) return "";
  std::error_code ec;
  const fs::path file = fs::canonical(fs::path(path).is_absolute() ? fs::path(path)
                                                                   : roots.front() / path, ec);
  if (ec || !fs::is_regular_file(file, ec)) return "";
  for (const fs::path& root : roots)
    if (!root.empty() && inside(root, file)) return file.string();
  return "";
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
