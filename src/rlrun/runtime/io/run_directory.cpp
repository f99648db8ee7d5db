#include "rlrun/runtime/io/run_directory.hpp"

#include <filesystem>

#include "rlrun/core/dir_handle.hpp"
#include "rlrun/core/errors.hpp"

namespace rlrun {

namespace fs = std::filesystem;

std::string create_run_directory(const std::string& out_dir, const std::string& name,
                                 uint64_t seed) {
  // out_dir is the user's (created as needed, their links followed); `name` below it and the
  // seed directory are opened without following links (core/dir_handle.hpp): a planted
  // `<out_dir>/<name> -> elsewhere` (a study's trials/trial_3, say) is refused.
  std::error_code ec;
  fs::create_directories(out_dir.empty() ? "." : out_dir, ec);
  if (ec) throw RuntimeFailure("cannot create " + out_dir + ": " + ec.message());
  const DirHandle base =
      DirHandle::open(out_dir.empty() ? "." : out_dir, DirHandle::LastLink::kFollow)
          .make_subdir(name);
  const std::string stem = "seed" + std::to_string(seed);
  // A bounded search: a path that "exists" whatever the suffix (a name the file system cuts
  // short, say) must end in an error, not spin (run names are checked when parsed).
  constexpr int kMaxAttempts = 10000;
  for (int attempt = 1; attempt <= kMaxAttempts; ++attempt) {
    const std::string dir = attempt == 1 ? stem : stem + "_" + std::to_string(attempt);
    // mkdir is atomic: an existing name (made by a run started at the same time, too) means
    // the next one.
    if (base.create_subdir(dir)) return (fs::path(out_dir) / name / dir).string();
  }
  throw RuntimeFailure("cannot create a run directory under " + base.path() + ": " + stem + " to " +
                       stem + "_" + std::to_string(kMaxAttempts) +
                       " all exist; choose another run.name or out_dir");
}

void write_text_atomic(const std::string& path, std::string_view text) {
  // The directory holding `path` is the caller's (resolved as usual); the file's own name is
  // replaced by renameat, never followed (core/dir_handle.hpp).
  const auto [dir, name] = DirHandle::open_parent(path);
  dir.write_atomic(name, text);
}

}  // namespace rlrun
