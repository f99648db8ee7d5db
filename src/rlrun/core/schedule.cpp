#include "rlrun/core/schedule.hpp"

#include <cmath>
#include <stdexcept>
#include "rlrun/core/float_format.hpp"

namespace rlrun {

namespace {
double parse_number(const std::string& text) {
  size_t used = 0;
  double v = 0;
  try {
    v = std::stod(text, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used == 0 || used != text.size())
    throw std::invalid_argument("expected a number or lin_<number>, got '" + text + "'");
  if (!std::isfinite(v))
    throw std::invalid_argument("expected a finite number or lin_<number>, got '" + text + "'");
  return v;
}

}  // namespace

Schedule Schedule::parse(const std::string& text) {
  if (text.rfind("lin_", 0) == 0) return linear(parse_number(text.substr(4)));
  return constant(parse_number(text));
}

std::string Schedule::str() const { return (linear_ ? "lin_" : "") + python_float_repr(initial_); }

}  // namespace rlrun
