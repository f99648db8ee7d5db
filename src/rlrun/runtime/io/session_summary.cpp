#include "rlrun/runtime/io/session_summary.hpp"

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstdlib>

#include "rlrun/core/plural.hpp"

namespace rlrun {

namespace {

constexpr const char* kTrained = "trained ";
constexpr const char* kInterrupted = "interrupted after ";

// Reads an integer at `at` and moves past it; false when there is none.
bool read_int(const std::string& line, size_t& at, int64_t& out) {
  if (at >= line.size()) return false;
  const char* begin = line.c_str() + at;
  char* end = nullptr;
  errno = 0;
  const long long v = std::strtoll(begin, &end, 10);
  if (end == begin || errno != 0) return false;
  out = v;
  at += static_cast<size_t>(end - begin);
  return true;
}

bool read_double(const std::string& line, size_t& at, double& out) {
  if (at >= line.size()) return false;
  const char* begin = line.c_str() + at;
  char* end = nullptr;
  const double v = std::strtod(begin, &end);
  if (end == begin) return false;
  out = v;
  at += static_cast<size_t>(end - begin);
  return true;
}

bool skip(const std::string& line, size_t& at, const std::string& text) {
  if (line.compare(at, text.size(), text) != 0) return false;
  at += text.size();
  return true;
}

}  // namespace

std::string format_session_summary(const SessionSummary& s) {
  std::string text = s.interrupted ? kInterrupted : kTrained;
  text += count_of(s.steps(), "step");
  if (s.start_timesteps != 0)
    text +=
        " (" + std::to_string(s.start_timesteps) + " -> " + std::to_string(s.end_timesteps) + ")";
  char rest[96];
  std::snprintf(rest, sizeof rest, " in %.2f s (%.0f steps/s)", s.wall_seconds,
                static_cast<double>(s.steps()) / std::max(s.wall_seconds, 1e-9));
  return text + rest;
}

std::optional<SessionSummary> parse_session_summary(const std::string& line) {
  SessionSummary s;
  size_t at = 0;
  if (skip(line, at, kInterrupted))
    s.interrupted = true;
  else if (!skip(line, at, kTrained))
    return std::nullopt;
  int64_t steps = 0;
  if (!read_int(line, at, steps) || !(skip(line, at, " steps") || skip(line, at, " step")))
    return std::nullopt;
  s.end_timesteps = steps;
  if (skip(line, at, " (")) {
    if (!read_int(line, at, s.start_timesteps) || !skip(line, at, " -> ") ||
        !read_int(line, at, s.end_timesteps) || !skip(line, at, ")"))
      return std::nullopt;
  }
  if (!skip(line, at, " in ") || !read_double(line, at, s.wall_seconds) || !skip(line, at, " s"))
    return std::nullopt;
  return s;
}

}  // namespace rlrun
