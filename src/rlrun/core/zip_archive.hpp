#pragma once
// Reading and writing zip files of named members (libzip). Writes are atomic: the archive is
// built under a temporary name in the same directory and renamed over the target, so a crash
// never leaves a half-written model (docs/experiments.md, "Output files").
#include <cstdint>
#include <map>
#include <string>
#include <vector>

namespace rlrun {

class DirHandle;  // core/dir_handle.hpp

using ZipMembers = std::map<std::string, std::vector<uint8_t>>;

// Throws RuntimeFailure with the path and libzip's reason.
void write_zip_atomic(const std::string& path, const ZipMembers& members);
// `name` in the open directory `dir` (a run directory's: its name is not followed as a link,
// nor is the directory looked up by its path again; core/dir_handle.hpp).
void write_zip_atomic(const DirHandle& dir, const std::string& name, const ZipMembers& members);
// Every member (directories left out), with the checks of core/zip_reader.hpp; refuses an
// archive whose members declare more than `max_total_bytes` together before reading any.
ZipMembers read_zip(const std::string& path, uint64_t max_total_bytes = uint64_t{1} << 30);

}  // namespace rlrun
