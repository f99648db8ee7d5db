#include "rlrun/core/trusted_values.hpp"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <vector>

#include "rlrun/core/shipped_data.hpp"

namespace rlrun {

namespace fs = std::filesystem;

namespace {

// `text` with every control character, DEL and backslash as \xNN: a value printed from
// untrusted text cannot move the cursor, end the line or hide what follows it.
std::string printable(const std::string& text) {
  static const char* hex = "0123456789abcdef";
  std::string out;
  for (const char ch : text) {
    const auto c = static_cast<unsigned char>(ch);
    if (c < 0x20 || c == 0x7f || c == '\\') {
      out += "\\x";
      out += hex[c >> 4];
      out += hex[c & 15];
    } else {
      out += ch;
    }
  }
  return out;
}

}  // namespace

std::string trust_alternative(const ConfigNode& n) {
  if (n.trust_option().empty()) return "";
  return " Or pass " + n.trust_option() + " to accept everything " + n.origin() +
         " names (each printed first).";
}

void require_vouched(const ConfigNode& n, const std::string& what, const std::string& value) {
  if (!n.trusted())
    n.fail(what + ", '" + value + "' named in " + n.origin() +
           ", which rlrun does not trust (model files, checkpoints, run directories, sweep "
           "manifests and zoo files may come from anyone; docs/security.md). If you trust it, pass "
           "--set " +
           n.path() + "=" + value + " (or another value) on the command line." +
           trust_alternative(n));
  if (n.accepted_as_a_whole())
    std::fprintf(stderr, "trusting %s (%s): %s = %s: %s\n", printable(n.origin()).c_str(),
                 n.trust_option().empty() ? "accepted" : n.trust_option().c_str(), n.path().c_str(),
                 printable(value).c_str(), what.c_str());
}

namespace {

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
  const fs::path file =
      fs::canonical(fs::path(path).is_absolute() ? fs::path(path) : roots.front() / path, ec);
  if (ec || !fs::is_regular_file(file, ec)) return "";
  for (const fs::path& root : roots)
    if (!root.empty() && inside(root, file)) return file.string();
  return "";
}

}  // namespace

void decode(const ConfigNode& n, ProgramPath& out) {
  const std::string value = n.as_string();
  if (value != out.value) require_vouched(n, "a program to run", value);
  out.value = value;
}

void decode(const ConfigNode& n, OutputPath& out) {
  const std::string value = n.as_string();
  if (value != out.value) require_vouched(n, "an output file", value);
  out.value = value;
}

void decode(const ConfigNode& n, SimulatorInput& out) {
  const std::string value = n.as_string();
  const bool own = n.trusted() && !n.accepted_as_a_whole();
  if (own || value == out.value) {
    out.value = value;
    return;
  }
  // A scenario shipped with rlrun needs no one's word; any other file does.
  if (const std::string shipped = shipped_file(value); !shipped.empty()) {
    out.value = shipped;
    return;
  }
  require_vouched(n, "a simulator input file (it can make the simulator write files)", value);
  out.value = value;
}

}  // namespace rlrun
