#pragma once
// Base64 (RFC 4648, section 4: the standard alphabet with '=' padding), as Python's
// base64.b64encode writes it: SB3 stores its cloudpickled `data` entries so.
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace rlrun {

// The bytes `text` encodes, or nullopt when it is not canonical base64 (a character outside
// the alphabet, whitespace, a length that is not a multiple of 4, misplaced padding).
std::optional<std::vector<uint8_t>> decode_base64(std::string_view text);
// The padded base64 text of `bytes`.
std::string encode_base64(const std::vector<uint8_t>& bytes);

}  // namespace rlrun
