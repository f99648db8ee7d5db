#include "rlrun/core/line_reader.hpp"

#include <unistd.h>

#include <cerrno>
#include <cstring>

#include "rlrun/core/checked_file.hpp"
#include "rlrun/core/errors.hpp"
#include "rlrun/core/regular_file.hpp"

namespace rlrun {

namespace {
constexpr size_t kBufferBytes = 1 << 16;
}  // namespace

LineReader::LineReader(FileDescriptor fd, std::string shown, uint64_t max_bytes,
                       size_t max_line_bytes, LongLines long_lines)
    : fd_(std::move(fd)),
      shown_(std::move(shown)),
      max_bytes_(max_bytes),
      max_line_bytes_(max_line_bytes),
      long_lines_(long_lines),
      buffer_(kBufferBytes) {}

bool LineReader::fill() {
  if (at_end_) return false;
  for (;;) {
    const ssize_t n = ::read(fd_.get(), buffer_.data(), buffer_.size());
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) throw RuntimeFailure("cannot read " + shown_ + ": " + describe_errno(errno));
    begin_ = 0;
    end_ = static_cast<size_t>(n);
    bytes_read_ += static_cast<uint64_t>(n);
    if (bytes_read_ > max_bytes_) refuse_oversized(shown_, max_bytes_);
    at_end_ = n == 0;
    return n > 0;
  }
}

bool LineReader::next(std::string& line) {
  line.clear();
  bool any = false;  // a last line without '\n' is a line too
  for (;;) {
    if (begin_ == end_ && !fill()) {
      if (any) ++lines_;
      return any;
    }
    any = true;
    const char* start = buffer_.data() + begin_;
    const void* newline = std::memchr(start, '\n', end_ - begin_);
    const size_t chunk =
        newline ? static_cast<size_t>(static_cast<const char*>(newline) - start) : end_ - begin_;
    if (line.size() + chunk > max_line_bytes_) {
      if (long_lines_ == LongLines::kRefuse)
        throw RuntimeFailure(shown_ + ":" + std::to_string(lines_ + 1) + ": a line longer than " +
                             describe_bytes(max_line_bytes_) +
                             ", the most rlrun reads of one "
                             "(docs/security.md, \"Bounds\")");
      line.append(start, max_line_bytes_ - std::min(line.size(), max_line_bytes_));
    } else {
      line.append(start, chunk);
    }
    begin_ += chunk;
    if (newline) {
      ++begin_;
      ++lines_;
      return true;
    }
  }
}

}  // namespace rlrun
