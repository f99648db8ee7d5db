#pragma once
// The run directory `<out_dir>/<name>/seed<N>/` (docs/experiments.md). An existing directory is
// never overwritten: the new run gets `seed<N>_2`, `seed<N>_3`, ... (as rl-zoo numbers its runs).
#include <cstdint>
#include <string>
#include <string_view>

namespace rlrun {

// Written into the run directory when training ends normally (not interrupted), last of all:
// a run directory with it is complete (`rlrun sweep run` skips it).
inline constexpr const char* kFinishedMarker = "finished";

// Creates and returns a fresh run directory. Throws RuntimeFailure if it cannot.
std::string create_run_directory(const std::string& out_dir, const std::string& name,
                                 uint64_t seed);

// Writes a text file atomically: a fresh temporary beside it (O_EXCL), every write checked,
// fsync, rename. Throws RuntimeFailure naming the file and errno (e.g. ENOSPC); the target then
// keeps its previous contents and no temporary is left.
void write_text_atomic(const std::string& path, std::string_view text);

}  // namespace rlrun
