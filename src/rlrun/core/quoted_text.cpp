#include "rlrun/core/quoted_text.hpp"

#include <algorithm>
#include <cstdint>
#include <cstdio>

namespace rlrun {

namespace {

// The length of the UTF-8 sequence at `s[i]` and its code point, or 0 when the bytes there are
// not one (a stray continuation byte, a cut or overlong sequence, a surrogate).
std::size_t utf8_sequence(std::string_view s, std::size_t i, uint32_t& code_point) {
  const auto byte = [&](std::size_t k) { return static_cast<unsigned char>(s[k]); };
  const unsigned char lead = byte(i);
  std::size_t length = 0;
  uint32_t minimum = 0;
  if (lead >= 0xC2 && lead <= 0xDF) {
    length = 2, code_point = lead & 0x1F, minimum = 0x80;
  } else if (lead >= 0xE0 && lead <= 0xEF) {
    length = 3, code_point = lead & 0x0F, minimum = 0x800;
  } else if (lead >= 0xF0 && lead <= 0xF4) {
    length = 4, code_point = lead & 0x07, minimum = 0x10000;
  } else {
    return 0;
  }
  if (i + length > s.size()) return 0;
  for (std::size_t k = 1; k < length; ++k) {
    if ((byte(i + k) & 0xC0) != 0x80) return 0;
    code_point = (code_point << 6) | (byte(i + k) & 0x3F);
  }
  if (code_point < minimum || code_point > 0x10FFFF ||
      (code_point >= 0xD800 && code_point <= 0xDFFF))
    return 0;
  return length;
}

std::string escape(const char* format, uint32_t value) {
  char buffer[16];
  std::snprintf(buffer, sizeof buffer, format, static_cast<unsigned>(value));
  return buffer;
}

// The visible form of the character at s[i] (and how many bytes it takes).
std::string visible_at(std::string_view s, std::size_t i, std::size_t& used) {
  const unsigned char c = static_cast<unsigned char>(s[i]);
  used = 1;
  if (c < 0x80) {
    if (c == '\n') return "\\n";
    if (c == '\r') return "\\r";
    if (c == '\t') return "\\t";
    if (c < 0x20 || c == 0x7F) return escape("\\x%02x", c);
    return std::string(1, static_cast<char>(c));
  }
  uint32_t code_point = 0;
  const std::size_t length = utf8_sequence(s, i, code_point);
  if (length == 0) return escape("\\x%02x", c);
  used = length;
  if (code_point <= 0x9F || code_point == 0x2028 || code_point == 0x2029 || code_point == 0xFEFF)
    return escape("\\u%04x", code_point);
  return std::string(s.substr(i, length));
}

}  // namespace

std::string quoted_text(std::string_view text, std::size_t max_bytes) {
  static constexpr std::string_view kEllipsis = "...";
  std::string out;
  std::size_t cut = 0;  // where to cut if the whole text does not fit: room left for "..."
  for (std::size_t i = 0; i < text.size();) {
    std::size_t used = 0;
    const std::string piece = visible_at(text, i, used);
    if (out.size() + piece.size() + kEllipsis.size() <= max_bytes) cut = out.size() + piece.size();
    out += piece;
    if (out.size() > max_bytes) {
      out.resize(cut);
      return out.append(kEllipsis);
    }
    i += used;
  }
  return out;
}

bool valid_utf8(std::string_view text) {
  for (std::size_t i = 0; i < text.size();) {
    uint32_t code_point = 0;
    const std::size_t length =
        static_cast<unsigned char>(text[i]) < 0x80 ? 1 : utf8_sequence(text, i, code_point);
    if (length == 0) return false;
    i += length;
  }
  return true;
}

std::string bounded_message(std::string_view message, std::size_t max_lines,
                            std::size_t max_line_bytes) {
  std::string out;
  std::size_t lines = 0, start = 0;
  while (start <= message.size()) {
    const std::size_t end = std::min(message.find('\n', start), message.size());
    if (lines == max_lines) {
      std::size_t rest = 1;
      for (std::size_t i = start; i < message.size(); ++i) rest += message[i] == '\n';
      return out + "\n(" + std::to_string(rest) + " more lines)";
    }
    if (lines++ > 0) out += '\n';
    out += quoted_text(message.substr(start, end - start), max_line_bytes);
    start = end + 1;
  }
  return out;
}

}  // namespace rlrun
