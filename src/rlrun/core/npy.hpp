#pragma once
// NumPy's .npy format, version 1.0 (numpy/lib/format.py): magic, header dict padded to a
// multiple of 64 bytes, raw little-endian data in C order. Lets `numpy.load("model.zip")` open
// rlrun model files directly.
//
// .npy bytes come from untrusted files (model files, checkpoints, observation logs): the header
// is parsed without exceptions from number conversion and without trusting the shape — every
// dimension and the byte count are overflow-checked, so a caller can compare the size the header
// implies with the size it has BEFORE it allocates anything for the data.
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "rlrun/core/tensor.hpp"

namespace rlrun {

// magic "\x93NUMPY" (6) + version (2) + header_len (2, little-endian) in format version 1.0.
inline constexpr std::size_t kNpyPreludeBytes = 10;
// numpy's own limit on dimensions (NPY_MAXDIMS of numpy 1.x); rlrun writes at most 2.
inline constexpr std::size_t kNpyMaxDims = 32;

struct NpyHeader {
  DType dtype = DType::kFloat32;
  std::vector<int64_t> shape;
  std::size_t header_bytes = 0;  // prelude + header dict: where the data starts
  uint64_t data_bytes = 0;       // product of the shape times the item size (overflow-checked)
};

// The header dict's length from the first kNpyPreludeBytes bytes. Throws std::runtime_error
// naming `what` (no magic, another format version).
std::size_t npy_header_length(const uint8_t* prelude, std::size_t size, const std::string& what);

// Parses prelude + header dict (`size` >= kNpyPreludeBytes + npy_header_length()). Accepts the
// dtypes rlrun writes ('<f4', '<f8', '<i8', '<u8'), C order only. Throws std::runtime_error
// naming `what` for anything else, a malformed dict, a dimension that is not a non-negative
// decimal integer or a size that does not fit in 63 bits.
NpyHeader parse_npy_header(const uint8_t* bytes, std::size_t size, const std::string& what);

std::vector<uint8_t> encode_npy(const Tensor& tensor);
// Throws std::runtime_error naming `what` on a malformed or unsupported file, or when the data
// is not exactly as long as the header says.
Tensor decode_npy(const std::vector<uint8_t>& bytes, const std::string& what);

}  // namespace rlrun
