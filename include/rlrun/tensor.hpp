#pragma once
// A named n-d array as stored in model files and checkpoints: dtype, shape (numpy C order) and
// raw bytes. Part of the plugin API (an env's saved state is a set of these); rlrun's own
// Eigen conversions live in src/rlrun/core/tensor.hpp.
#include <cstdint>
#include <map>
#include <string>
#include <type_traits>
#include <vector>

namespace rlrun {

// kUInt8: image observations kept as bytes (a replay buffer's stored observations).
enum class DType : int32_t { kFloat32 = 0, kFloat64 = 1, kInt64 = 2, kUInt64 = 3, kUInt8 = 4 };

inline std::size_t dtype_size(DType t) {
  switch (t) {
    case DType::kFloat32: return 4;
    case DType::kUInt8: return 1;
    default: return 8;
  }
}

struct Tensor {
  DType dtype = DType::kFloat32;
  std::vector<int64_t> shape;
  std::vector<uint8_t> bytes;

  int64_t numel() const {
    int64_t n = 1;
    for (auto d : shape) n *= d;
    return n;
  }
  template <class T>
  const T* data() const {
    return reinterpret_cast<const T*>(bytes.data());
  }
  template <class T>
  T* data() {
    return reinterpret_cast<T*>(bytes.data());
  }
};

using TensorMap = std::map<std::string, Tensor>;

template <class T>
constexpr DType dtype_of() {
  static_assert(std::is_same_v<T, float> || std::is_same_v<T, double> ||
                    std::is_same_v<T, int64_t> || std::is_same_v<T, uint64_t> ||
                    std::is_same_v<T, uint8_t>,
                "tensors hold float, double, int64_t, uint64_t or uint8_t");
  if constexpr (std::is_same_v<T, float>) return DType::kFloat32;
  if constexpr (std::is_same_v<T, double>) return DType::kFloat64;
  if constexpr (std::is_same_v<T, int64_t>) return DType::kInt64;
  if constexpr (std::is_same_v<T, uint8_t>) return DType::kUInt8;
  return DType::kUInt64;
}

}  // namespace rlrun
