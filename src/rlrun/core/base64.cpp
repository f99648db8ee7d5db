#include "rlrun/core/base64.hpp"

#include <algorithm>

namespace rlrun {

namespace {

int sextet(char c) {
  if (c >= 'A' && c <= 'Z') return c - 'A';
  if (c >= 'a' && c <= 'z') return c - 'a' + 26;
  if (c >= '0' && c <= '9') return c - '0' + 52;
  if (c == '+') return 62;
  if (c == '/') return 63;
  return -1;
}

}  // namespace

std::optional<std::vector<uint8_t>> decode_base64(std::string_view text) {
  if (text.size() % 4 != 0) return std::nullopt;
  std::vector<uint8_t> out;
  out.reserve(text.size() / 4 * 3);
  for (size_t at = 0; at < text.size(); at += 4) {
    const bool last = at + 4 == text.size();
    const int padding = last ? (text[at + 3] == '=') + (text[at + 2] == '=') : 0;
    if (padding == 1 && text[at + 2] == '=') return std::nullopt;  // "x=y=" style
    uint32_t group = 0;
    for (int i = 0; i < 4 - padding; ++i) {
      const int v = sextet(text[at + static_cast<size_t>(i)]);
      if (v < 0) return std::nullopt;
      group |= static_cast<uint32_t>(v) << (18 - 6 * i);
    }
    out.push_back(static_cast<uint8_t>(group >> 16));
    if (padding < 2) out.push_back(static_cast<uint8_t>(group >> 8));
    if (padding < 1) out.push_back(static_cast<uint8_t>(group));
  }
  return out;
}

std::string encode_base64(const std::vector<uint8_t>& bytes) {
  static constexpr char kAlphabet[] =
      "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  out.reserve((bytes.size() + 2) / 3 * 4);
  for (size_t at = 0; at < bytes.size(); at += 3) {
    const size_t n = std::min<size_t>(3, bytes.size() - at);
    uint32_t group = 0;
    for (size_t i = 0; i < n; ++i) group |= static_cast<uint32_t>(bytes[at + i]) << (16 - 8 * i);
    for (size_t i = 0; i < 4; ++i)
      out.push_back(i <= n ? kAlphabet[(group >> (18 - 6 * i)) & 63] : '=');
  }
  return out;
}

}  // namespace rlrun
