#pragma once
// NumPy's .npy format, version 1.0 (numpy/lib/format.py): magic, header dict padded to a
// multiple of 64 bytes, raw little-endian data in C order. Lets `numpy.load("model.zip")` open
// rlrun model files directly.
#include <string>
#include <vector>

#include "rlrun/core/tensor.hpp"

namespace rlrun {

std::vector<uint8_t> encode_npy(const Tensor& tensor);
// Throws std::runtime_error naming `what` on a malformed or unsupported file.
Tensor decode_npy(const std::vector<uint8_t>& bytes, const std::string& what);

}  // namespace rlrun
