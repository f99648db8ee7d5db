#pragma once
// A copy of `s` with A-Z as a-z and every other byte as it was (locale-free: ids and names, not
// prose).
#include <string>

namespace rlrun {

inline std::string ascii_lower(std::string s) {
  for (char& c : s)
    if (c >= 'A' && c <= 'Z') c = static_cast<char>(c - 'A' + 'a');
  return s;
}

}  // namespace rlrun
