// Fuzz target: decode_npy on arbitrary bytes (core/npy.hpp). It may refuse with
// std::runtime_error; what it accepts must be self-consistent and survive encode/decode.
#include <cstdint>
#include <cstdlib>
#include <stdexcept>
#include <vector>

#include "rlrun/core/npy.hpp"

using namespace rlrun;

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::vector<uint8_t> bytes(data, data + size);
  Tensor t;
  try {
    t = decode_npy(bytes, "fuzz.npy");
  } catch (const std::runtime_error&) {
    return 0;
  }
  if (t.bytes.size() != static_cast<size_t>(t.numel()) * dtype_size(t.dtype)) std::abort();
  const Tensor again = decode_npy(encode_npy(t), "again.npy");
  if (again.shape != t.shape || again.dtype != t.dtype || again.bytes != t.bytes) std::abort();
  return 0;
}
