#include "rlrun/deploy/c_comment_text.hpp"

#include <cstdint>
#include <cstring>

namespace rlrun {

namespace {

bool passes(uint8_t c) {
  if ((c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9')) return true;
  // C99 5.2.1's basic source character set, less \ * ? (and %, the escape character).
  static constexpr char kPunctuation[] = " !\"#&'()+,-./:;<=>[]^_{|}~";
  return c != 0 && std::strchr(kPunctuation, c) != nullptr;
}

}  // namespace

std::string c_comment_text(std::string_view text) {
  static constexpr char kHex[] = "0123456789ABCDEF";
  std::string out;
  out.reserve(text.size());
  for (const char ch : text) {
    const auto c = static_cast<uint8_t>(ch);
    if (passes(c)) {
      out += ch;
    } else {
      out += '%';
      out += kHex[c >> 4];
      out += kHex[c & 0xF];
    }
  }
  return out;
}

}  // namespace rlrun
