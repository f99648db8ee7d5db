#pragma once
// Value constraints of config fields, declared where the field is listed:
//     v("gamma", gamma, "discount factor", in_range(0.0, 1.0));
// The strict reader (config_fields.hpp) checks them while decoding, so a bad value is reported
// with its file:line:col before anything is built or trained; `rlrun list ID` shows them.
// Ranges follow SB3's own assertions where it has them (e.g. ppo.py: batch_size > 1,
// clip_range > 0) and plain sense where it has none (gamma is a discount in [0, 1]).
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "rlrun/core/float_format.hpp"

namespace rlrun {

// A closed, open or half-open interval of numbers. NaN is outside every interval.
struct Bounds {
  double low = -std::numeric_limits<double>::infinity();
  double high = std::numeric_limits<double>::infinity();
  bool low_open = false;
  bool high_open = false;

  bool contains(double v) const {
    if (std::isnan(v)) return false;
    const bool above = low_open ? v > low : v >= low;
    const bool below = high_open ? v < high : v <= high;
    return above && below;
  }
  // "in [0, 1]", ">= 1", "> 0".
  std::string describe() const {
    const bool has_low = std::isfinite(low), has_high = std::isfinite(high);
    if (has_low && has_high)
      return std::string("in ") + (low_open ? "(" : "[") + number(low) + ", " + number(high) +
             (high_open ? ")" : "]");
    if (has_low) return (low_open ? "> " : ">= ") + number(low);
    if (has_high) return (high_open ? "< " : "<= ") + number(high);
    return "any number";
  }
  Bounds open_low() const {
    Bounds b = *this;
    b.low_open = true;
    return b;
  }
  // "" or "must be in [0, 1], got 2".
  std::string problem(double v) const {
    if (contains(v)) return "";
    return "must be " + describe() + ", got " + number(v);
  }

 private:
  static std::string number(double v) {
    if (std::floor(v) == v && std::abs(v) < 1e15) return std::to_string(static_cast<int64_t>(v));
    return python_float_repr(v);
  }
};

inline Bounds at_least(double low) { return {low, std::numeric_limits<double>::infinity()}; }
inline Bounds greater_than(double low) {
  return {low, std::numeric_limits<double>::infinity(), true, false};
}
inline Bounds in_range(double low, double high) { return {low, high}; }
inline Bounds positive() { return greater_than(0.0); }
inline Bounds non_negative() { return at_least(0.0); }
inline Bounds unit_interval() { return in_range(0.0, 1.0); }

// A string that must be one of a few names (an enum in YAML).
struct OneOf {
  std::vector<std::string> names;
  std::string describe() const {
    std::string s = "one of ";
    for (size_t i = 0; i < names.size(); ++i) s += (i ? ", " : "") + names[i];
    return s;
  }
};

// A name that becomes part of a path inside a directory rlrun owns (a run name under out_dir):
// plain names separated by '/', none empty, '.' or '..', not absolute, no control characters
// (a NUL would silently cut the path short).
struct RelativeName {
  std::string describe() const { return "a relative name without '..'"; }
  std::string problem(const std::string& v) const {
    if (v.empty()) return "must not be empty";
    for (unsigned char c : v)
      if (c < 0x20 || c == 0x7f) return "must not contain control characters (a NUL, a newline)";
    if (v.front() == '/') return "must be a relative name, not an absolute path ('" + v + "')";
    size_t start = 0;
    while (start <= v.size()) {
      const size_t end = std::min(v.find('/', start), v.size());
      const std::string part = v.substr(start, end - start);
      if (part.empty() || part == "." || part == "..")
        return "must not contain empty, '.' or '..' parts ('" + v + "' would leave its directory)";
      start = end + 1;
    }
    if (v.size() > 200) return "is longer than 200 characters";
    return "";
  }
};

// A directory the user names (out_dir): not empty, no control characters.
struct DirectoryPath {
  std::string describe() const { return "a directory path"; }
  std::string problem(const std::string& v) const {
    if (v.empty()) return "must not be empty (use . for the current directory)";
    for (unsigned char c : v)
      if (c < 0x20 || c == 0x7f) return "must not contain control characters (a NUL, a newline)";
    if (v.size() > 1024) return "is longer than 1024 characters";
    return "";
  }
};

}  // namespace rlrun

namespace rlrun {

// A problem found by a component's own cross-field check (one that needs more than one value,
// or the env's spaces): `key` is the dotted path of the value to blame inside the component's
// section ("batch_size", "policy.net_arch"), so the message can point at its file:line:col.
struct ConfigProblem {
  std::string key;
  std::string message;
};
using ConfigProblems = std::vector<ConfigProblem>;

}  // namespace rlrun
