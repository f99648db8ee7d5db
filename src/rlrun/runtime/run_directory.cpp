#include "rlrun/runtime/run_directory.hpp"

#include <filesystem>
#include <fstream>

#include "rlrun/core/errors.hpp"

namespace rlrun {

namespace fs = std::filesystem;

std::string create_run_directory(const std::string& out_dir, const std::string& name, uint64_t seed) {
  const fs::path base = fs::path(out_dir) / name;
  const std::string stem = "seed" + std::to_string(seed);
  std::error_code ec;
  fs::create_directories(base, ec);
  if (ec) throw RuntimeFailure("cannot create " + base.string() + ": " + ec.message());
  // A bounded search: a path that "exists" whatever the suffix (a name the file system cuts
  // short, say) must end in an error, not spin (run names are checked when parsed).
  constexpr int kMaxAttempts = 10000;
  for (int attempt = 1; attempt <= kMaxAttempts; ++attempt) {
    const fs::path dir = base / (attempt == 1 ? stem : stem + "_" + std::to_string(attempt));
    // create_directory returns false if it already existed: try the next name.
    if (fs::create_directory(dir, ec)) return dir.string();
    if (ec) throw RuntimeFailure("cannot create " + dir.string() + ": " + ec.message());
  }
  throw RuntimeFailure("cannot create a run directory under " + base.string() + ": " + stem +
                       " to " + stem + "_" + std::to_string(kMaxAttempts) +
                       " all exist; choose another run.name or out_dir");
}

void write_text_atomic(const std::string& path, const std::string& text) {
  const std::string temp = path + ".tmp";
  {
    std::ofstream out(temp, std::ios::trunc);
    out << text;
    if (!out) throw RuntimeFailure("cannot write " + temp);
  }
  std::error_code ec;
  fs::rename(temp, path, ec);
  if (ec) throw RuntimeFailure("cannot rename " + temp + " to " + path + ": " + ec.message());
}

}  // namespace rlrun
