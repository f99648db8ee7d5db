#pragma once
// Text from a file rlrun does not trust, quoted in an error message, a note or a comment of a
// written file: one line of printable characters, at most a few hundred bytes. So a hostile
// file can neither add lines to what rlrun prints or writes (a newline, a carriage return, a
// Unicode line separator would start one) nor make one message hundreds of kilobytes long
// (docs/security.md).
#include <cstddef>
#include <string>
#include <string_view>

namespace rlrun {

inline constexpr std::size_t kMaxQuotedBytes = 200;

// `text` with each control character (C0, DEL, C1), line or paragraph separator (U+2028,
// U+2029), byte order mark (U+FEFF) and byte that is not UTF-8 written as a visible escape
// (\n, \r, \t, \x1b, \u2028), and cut to at most `max_bytes` bytes, ending in "..." when cut.
std::string quoted_text(std::string_view text, std::size_t max_bytes = kMaxQuotedBytes);

// True when `text` is UTF-8: no stray continuation byte, cut or overlong sequence, surrogate or
// code point past U+10FFFF.
bool valid_utf8(std::string_view text);

// An error message (lines separated by '\n') that may quote such text anywhere, made safe to
// print: each line quoted_text and at most `max_line_bytes` long, at most `max_lines` lines
// (then a line saying how many more there were).
std::string bounded_message(std::string_view message, std::size_t max_lines = 40,
                            std::size_t max_line_bytes = 1000);

}  // namespace rlrun
