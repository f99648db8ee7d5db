#pragma once
// The lines of a text file a run directory or study holds (progress.csv, log.txt, the monitor
// files), read through a fixed buffer within two bounds: the whole file and one line. Memory
// stays at one line whatever the file holds, so a crafted file costs at most a bounded scan.
#include <cstdint>
#include <string>
#include <vector>

#include "rlrun/core/file_descriptor.hpp"

namespace rlrun {

class LineReader {
 public:
  // What a line longer than the bound does: refuse the file (data that must be whole: CSV
  // rows), or give its first max_line_bytes and skip the rest (text only scanned: log.txt).
  enum class LongLines { kRefuse, kCut };

  // `fd` open for reading (core/regular_file.hpp); `shown` names the file in messages.
  LineReader(FileDescriptor fd, std::string shown, uint64_t max_bytes, size_t max_line_bytes,
             LongLines long_lines = LongLines::kRefuse);

  // The next line without its '\n' (a last line without one too); false at the end. Throws
  // RuntimeFailure naming the file and the bound when it holds more than max_bytes, or
  // (kRefuse) a line longer than max_line_bytes.
  bool next(std::string& line);
  // Lines returned so far.
  uint64_t lines() const { return lines_; }
  const std::string& shown() const { return shown_; }

 private:
  bool fill();

  FileDescriptor fd_;
  std::string shown_;
  uint64_t max_bytes_;
  size_t max_line_bytes_;
  LongLines long_lines_;
  std::vector<char> buffer_;
  size_t begin_ = 0, end_ = 0;
  uint64_t bytes_read_ = 0;
  uint64_t lines_ = 0;
  bool at_end_ = false;
};

}  // namespace rlrun
