#pragma once
// Text for protobuf `string` fields (ONNX metadata and names, docs/security.md): protobuf
// requires them to be valid UTF-8 (a parser in Python or C++ refuses the whole file
// otherwise), and a model file's meta.json may hold any bytes.
#include <string>
#include <string_view>

namespace rlrun {

// `text` as printable UTF-8: well-formed sequences of printable characters pass unchanged;
// a backslash becomes `\\`, and every byte of a control character (C0, DEL, C1) or of an invalid
// sequence becomes `\xNN` (two hex digits), so the result is always valid UTF-8 and the
// original bytes can be read back from it. Unlike quoted_text (core/quoted_text.hpp, for
// messages), nothing is cut: metadata keeps all of its text. valid_utf8 is there too.
std::string printable_utf8(std::string_view text);

}  // namespace rlrun
