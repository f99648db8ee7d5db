#pragma once
// Readable Catch2 failures for colours: "Rgb(202, 152, 101)" instead of "{?}".
#include <ostream>

#include "rlrun/frame.hpp"

namespace rlrun {
inline std::ostream& operator<<(std::ostream& out, const Rgb& c) {
  return out << "Rgb(" << int(c.r) << ", " << int(c.g) << ", " << int(c.b) << ")";
}
}  // namespace rlrun
