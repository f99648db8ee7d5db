#include "rlrun/core/utf8_text.hpp"

#include <cstdint>

namespace rlrun {

namespace {

// Bytes of the well-formed UTF-8 sequence at text[at], or 0 (Unicode 15, table 3-7).
size_t sequence_length(std::string_view text, size_t at) {
  const auto byte = [&](size_t k) { return static_cast<uint8_t>(text[at + k]); };
  const size_t left = text.size() - at;
  const uint8_t b0 = byte(0);
  if (b0 < 0x80) return 1;
  const auto continuation = [&](size_t k, uint8_t low = 0x80, uint8_t high = 0xBF) {
    return k < left && byte(k) >= low && byte(k) <= high;
  };
  if (b0 >= 0xC2 && b0 <= 0xDF) return continuation(1) ? 2 : 0;
  if (b0 >= 0xE0 && b0 <= 0xEF) {
    const uint8_t low = b0 == 0xE0 ? 0xA0 : 0x80;   // no overlong form
    const uint8_t high = b0 == 0xED ? 0x9F : 0xBF;  // no surrogate
    return continuation(1, low, high) && continuation(2) ? 3 : 0;
  }
  if (b0 >= 0xF0 && b0 <= 0xF4) {
    const uint8_t low = b0 == 0xF0 ? 0x90 : 0x80;   // no overlong form
    const uint8_t high = b0 == 0xF4 ? 0x8F : 0xBF;  // nothing beyond U+10FFFF
    return continuation(1, low, high) && continuation(2) && continuation(3) ? 4 : 0;
  }
  return 0;
}

// U+0080..U+009F, the C1 control characters (0xC2 0x80..0x9F).
bool is_c1_control(std::string_view text, size_t at) {
  return static_cast<uint8_t>(text[at]) == 0xC2 && at + 1 < text.size() &&
         static_cast<uint8_t>(text[at + 1]) < 0xA0;
}

void append_hex_escape(std::string& out, uint8_t byte) {
  static constexpr char kHex[] = "0123456789abcdef";
  out += "\\x";
  out += kHex[byte >> 4];
  out += kHex[byte & 0xF];
}

}  // namespace

std::string printable_utf8(std::string_view text) {
  std::string out;
  out.reserve(text.size());
  for (size_t at = 0; at < text.size();) {
    const auto byte = static_cast<uint8_t>(text[at]);
    const size_t n = sequence_length(text, at);
    if (byte == '\\') {
      out += "\\\\";
    } else if (n == 0 || byte < 0x20 || byte == 0x7F || is_c1_control(text, at)) {
      append_hex_escape(out, byte);
      at += 1;
      continue;
    } else {
      out.append(text.substr(at, n));
    }
    at += n;
  }
  return out;
}

}  // namespace rlrun
