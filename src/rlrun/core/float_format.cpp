#include "rlrun/core/float_format.hpp"

#include <cmath>
#include <cstdio>
#include <cstdlib>

namespace rlrun {

std::string python_float_repr(double value) {
  if (std::isnan(value)) return "nan";
  if (std::isinf(value)) return value > 0 ? "inf" : "-inf";
  char buffer[40];
  for (int precision = 1; precision <= 17; ++precision) {
    std::snprintf(buffer, sizeof buffer, "%.*g", precision, value);
    if (std::strtod(buffer, nullptr) == value) break;
  }
  std::string s = buffer;
  // %g writes integral values without a point ("21"); Python writes "21.0". Exponents: %g
  // gives "1e-05" like Python; Python switches to exponents at 1e16, %g at the precision,
  // which only matters for huge integral values (written "1e+16" vs "1e+16": same).
  if (s.find_first_of(".en") == std::string::npos) s += ".0";
  return s;
}

}  // namespace rlrun
