#include "cli_values.hpp"

#include <charconv>
#include <cmath>
#include <cstdlib>
#include <optional>

namespace rlrun::cli {

namespace {

// Plain decimal digits (an optional leading '+'), exactly; nullopt when not or out of range.
std::optional<uint64_t> plain_digits(const std::string& text) {
  const char* begin = text.data() + (!text.empty() && text[0] == '+' ? 1 : 0);
  const char* end = text.data() + text.size();
  uint64_t value = 0;
  const auto [stop, error] = std::from_chars(begin, end, value);
  if (begin == end || stop != end || error != std::errc()) return std::nullopt;
  return value;
}

// An integer as config files write it (core/config_node.cpp as_int): digits with optional '_'
// separators and sign, or a number like 1e5 that is an exact integer (below 9e15, where every
// double is still one). nullopt when the text is no integer or one beyond int64.
std::optional<int64_t> config_integer(const std::string& typed) {
  std::string text;
  for (char c : typed)
    if (c != '_') text += c;
  const char* begin = text.data() + (!text.empty() && text[0] == '+' ? 1 : 0);
  const char* end = text.data() + text.size();
  int64_t exact = 0;
  const auto [stop, error] = std::from_chars(begin, end, exact);
  if (begin != end && stop == end) {
    if (error == std::errc()) return exact;
    return std::nullopt;
  }
  char* parsed_end = nullptr;
  const double v = std::strtod(text.c_str(), &parsed_end);
  if (text.empty() || parsed_end != text.c_str() + text.size() || !std::isfinite(v) ||
      std::floor(v) != v || std::abs(v) >= 9.0e15)
    return std::nullopt;
  return static_cast<int64_t>(v);
}

std::string integer_rule(int64_t min, int64_t max) {
  if (max == std::numeric_limits<int>::max() || max == std::numeric_limits<int64_t>::max())
    return "must be an integer >= " + std::to_string(min);
  if (max == min + 1) return "must be " + std::to_string(min) + " or " + std::to_string(max);
  return "must be an integer from " + std::to_string(min) + " to " + std::to_string(max);
}

}  // namespace

CLI::Validator seed_value() {
  return CLI::Validator(
      [](std::string& text) -> std::string {
        const std::optional<uint64_t> seed = plain_digits(text);
        if (seed && *seed <= kMaxSeed) return "";
        return "seeds are integers from 0 to " + std::to_string(kMaxSeed) + " (2^63 - 1), got '" +
               text + "'";
      },
      "0..2^63-1", "seed");
}

CLI::Validator integer_in(int64_t min, int64_t max) {
  const std::string rule = integer_rule(min, max);
  return CLI::Validator(
      [min, max, rule](std::string& text) -> std::string {
        const std::optional<int64_t> value = config_integer(text);
        if (value && *value >= min && *value <= max) {
          text = std::to_string(*value);  // what the option's integer type reads
          return "";
        }
        return rule + ", got '" + text + "'";
      },
      max == std::numeric_limits<int>::max() || max == std::numeric_limits<int64_t>::max()
          ? ">= " + std::to_string(min)
          : std::to_string(min) + ".." + std::to_string(max),
      "integer_in");
}

CLI::Validator positive_number(double max) {
  char max_text[32];
  std::snprintf(max_text, sizeof max_text, "%g", max);
  const std::string rule = std::string("must be a number > 0 and <= ") + max_text;
  return CLI::Validator(
      [max, rule](std::string& text) -> std::string {
        char* end = nullptr;
        const double v = std::strtod(text.c_str(), &end);
        if (!text.empty() && end == text.c_str() + text.size() && std::isfinite(v) && v > 0 &&
            v <= max)
          return "";
        return rule + ", got '" + text + "'";
      },
      std::string("(0, ") + max_text + "]", "positive_number");
}

}  // namespace rlrun::cli
