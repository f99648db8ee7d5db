#include "rlrun/core/float_format.hpp"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdlib>

namespace rlrun {

std::string python_float_repr(double value) {
  if (std::isnan(value)) return "nan";
  if (std::isinf(value)) return value > 0 ? "inf" : "-inf";
  if (value == 0.0) return std::signbit(value) ? "-0.0" : "0.0";
  // Shortest round-tripping significand, as Python's repr (float_repr_style 'short': the
  // fewest digits that read back to the same double, the closest such when there are several),
  // which is what std::to_chars without a precision gives. (It replaced trying "%.*e" with
  // 0..16 digits and reading each back: that was 2 % of a PPO run writing monitor.csv.)
  char buffer[64];
  // (A double needs at most 24 characters here, so the buffer always suffices.)
  const std::to_chars_result written =
      std::to_chars(buffer, buffer + sizeof buffer, value, std::chars_format::scientific);
  const std::string sci(buffer, written.ptr);  // e.g. "-1.2345e-05"
  const auto e_pos = sci.find('e');
  const int exponent = std::atoi(sci.c_str() + e_pos + 1);
  std::string digits;
  for (size_t i = 0; i < e_pos; ++i)
    if (std::isdigit(static_cast<unsigned char>(sci[i]))) digits += sci[i];
  const std::string sign = value < 0 ? "-" : "";
  // Python uses fixed notation for 1e-4 <= |x| < 1e16, else scientific.
  if (exponent >= -4 && exponent < 16) {
    std::string out = sign;
    if (exponent >= 0) {
      const size_t int_digits = static_cast<size_t>(exponent) + 1;
      out.append(digits, 0, std::min(int_digits, digits.size()));
      out.append(int_digits > digits.size() ? int_digits - digits.size() : 0, '0');
      out += '.';
      if (digits.size() > int_digits)
        out.append(digits, int_digits, std::string::npos);
      else
        out += '0';
    } else {
      out += "0.";
      out.append(static_cast<size_t>(-exponent - 1), '0');
      out += digits;
    }
    return out;
  }
  char exp_text[16];
  std::snprintf(exp_text, sizeof exp_text, "e%c%02d", exponent < 0 ? '-' : '+', std::abs(exponent));
  std::string out = sign;
  out += digits[0];
  if (digits.size() > 1) {
    out += '.';
    out.append(digits, 1, std::string::npos);
  }
  out += exp_text;
  return out;
}

std::string float32_text(float value) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.9g", static_cast<double>(value));
  return buffer;
}

}  // namespace rlrun
