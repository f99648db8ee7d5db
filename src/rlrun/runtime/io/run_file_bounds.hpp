#pragma once
// How much rlrun reads of each file a run directory holds. Run directories may come from anyone
// (docs/security.md, "Bounds"): each file is opened without following links, must be regular
// (core/dir_handle.hpp), and is read within these bounds, each a few times what the longest
// real run writes. A file over its bound is refused with its name and the bound.
#include <cstddef>
#include <cstdint>

namespace rlrun {

// progress.csv, evaluations.csv and each `<i>.monitor.csv`: a 10^8-step run logging a
// 600-byte progress row every 2048 steps writes 30 MB; a monitor file one 30-byte row per
// episode. Each row is read whole.
inline constexpr uint64_t kMaxRunCsvBytes = uint64_t{256} << 20;
inline constexpr size_t kMaxRunCsvLineBytes = size_t{1} << 20;
// The values a CSV file becomes in memory (8 bytes each): a row shorter than the header is
// padded with NaN, so a wide header over short rows could otherwise cost far more than the
// file's bytes.
inline constexpr uint64_t kMaxRunCsvValues = kMaxRunCsvBytes / 8;
// log.txt is only scanned for the sessions' summary lines (runtime/io/session_summary.hpp):
// line by line, longer lines cut, so memory stays at one line.
inline constexpr uint64_t kMaxRunLogBytes = uint64_t{1} << 30;
inline constexpr size_t kMaxRunLogLineBytes = size_t{64} << 10;
// The `finished` marker: "timesteps N\n".
inline constexpr uint64_t kMaxRunMarkerBytes = 4096;

}  // namespace rlrun
