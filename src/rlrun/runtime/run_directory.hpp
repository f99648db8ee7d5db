#pragma once
// The run directory `<out_dir>/<name>/seed<N>/` (DESIGN.md §5). An existing directory is never
// overwritten: the new run gets `seed<N>_2`, `seed<N>_3`, ... (as rl-zoo numbers its runs).
#include <cstdint>
#include <string>

namespace rlrun {

// Creates and returns a fresh run directory. Throws RuntimeFailure if it cannot.
std::string create_run_directory(const std::string& out_dir, const std::string& name, uint64_t seed);

// Writes a text file atomically (temp file + rename).
void write_text_atomic(const std::string& path, const std::string& text);

}  // namespace rlrun
