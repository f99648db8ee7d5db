#pragma once
// Spaces for plugin envs: Gymnasium's Box, Discrete, MultiDiscrete and MultiBinary
// (gymnasium/spaces/*.py) as one plain value. Every sample is a flat float32 vector: a
// Discrete value is one float holding the integer, MultiDiscrete / MultiBinary one float per
// entry. rlrun checks the space when it loads the env (e.g. Box low <= high) and reports
// problems naming the env.
#include <cstdint>
#include <utility>
#include <vector>

namespace rlrun::api {

enum class SpaceKind : int32_t { kBox = 0, kDiscrete = 1, kMultiDiscrete = 2, kMultiBinary = 3 };

struct Space {
  SpaceKind kind = SpaceKind::kBox;
  std::vector<int> shape;     // Box: numpy shape; others: filled by the constructors below
  std::vector<float> low;     // Box: lower bound of each element (row-major), may be -inf
  std::vector<float> high;    // Box: upper bound of each element, may be +inf
  int64_t n = 0;              // Discrete: number of values; MultiBinary: number of bits
  int64_t start = 0;          // Discrete: the first value (Gymnasium's `start`)
  std::vector<int64_t> nvec;  // MultiDiscrete: number of values of each entry

  // gymnasium.spaces.Box(low, high, shape, dtype=np.float32)
  static Space box(float low, float high, std::vector<int> shape) {
    int count = 1;
    for (int d : shape) count *= d;
    Space s;
    s.kind = SpaceKind::kBox;
    s.shape = std::move(shape);
    s.low.assign(static_cast<size_t>(count > 0 ? count : 0), low);
    s.high.assign(s.low.size(), high);
    return s;
  }
  // Box with one bound per element; shape (low.size(),).
  static Space box(std::vector<float> low, std::vector<float> high) {
    Space s;
    s.kind = SpaceKind::kBox;
    s.shape = {static_cast<int>(low.size())};
    s.low = std::move(low);
    s.high = std::move(high);
    return s;
  }
  // gymnasium.spaces.Discrete(n, start)
  static Space discrete(int64_t n, int64_t start = 0) {
    Space s;
    s.kind = SpaceKind::kDiscrete;
    s.n = n;
    s.start = start;
    return s;
  }
  // gymnasium.spaces.MultiDiscrete(nvec)
  static Space multi_discrete(std::vector<int64_t> nvec) {
    Space s;
    s.kind = SpaceKind::kMultiDiscrete;
    s.shape = {static_cast<int>(nvec.size())};
    s.nvec = std::move(nvec);
    return s;
  }
  // gymnasium.spaces.MultiBinary(n)
  static Space multi_binary(int n) {
    Space s;
    s.kind = SpaceKind::kMultiBinary;
    s.shape = {n};
    s.n = n;
    return s;
  }

  // Floats in one flat sample.
  int flat_dim() const {
    switch (kind) {
      case SpaceKind::kDiscrete:
        return 1;
      case SpaceKind::kMultiDiscrete:
        return static_cast<int>(nvec.size());
      case SpaceKind::kMultiBinary:
        return static_cast<int>(n);
      case SpaceKind::kBox:
        break;
    }
    return static_cast<int>(low.size());
  }
};

}  // namespace rlrun::api
