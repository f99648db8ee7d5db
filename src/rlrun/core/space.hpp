#pragma once
// Gymnasium spaces (gymnasium/spaces/*.py) as one value type. Every sample is a flat float32
// vector: a Discrete value is one float holding the integer, MultiDiscrete / MultiBinary one
// float per entry. That keeps env I/O, buffers and networks on one data type.
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "rlrun/core/rng.hpp"

namespace rlrun {

enum class SpaceKind { kBox, kDiscrete, kMultiDiscrete, kMultiBinary };

class Space {
 public:
  Space() = default;

  // Box(low, high, shape): bounds per element (flattened, row-major like numpy).
  static Space box(std::vector<float> low, std::vector<float> high, std::vector<int> shape = {});
  // Box with the same bound for every element.
  static Space box(float low, float high, std::vector<int> shape);
  // Discrete(n, start): values start, ..., start + n - 1.
  static Space discrete(int64_t n, int64_t start = 0);
  static Space multi_discrete(std::vector<int64_t> nvec);
  static Space multi_binary(int n);

  SpaceKind kind() const { return kind_; }
  bool is_box() const { return kind_ == SpaceKind::kBox; }
  bool is_discrete() const { return kind_ == SpaceKind::kDiscrete; }

  // Number of floats in one flat sample (Discrete: 1).
  int flat_dim() const;
  const std::vector<int>& shape() const { return shape_; }
  const std::vector<float>& low() const { return low_; }
  const std::vector<float>& high() const { return high_; }
  int64_t n() const { return n_; }
  int64_t start() const { return start_; }
  const std::vector<int64_t>& nvec() const { return nvec_; }

  bool contains(std::span<const float> x) const;
  // Uniform sample as gymnasium does (Box: uniform on bounded dims, normal/exponential on
  // unbounded ones; Discrete: uniform integer).
  void sample(Rng& rng, std::span<float> out) const;
  // Readable form, e.g. "Box(-2.0, 2.0, (1,), float32)" or "Discrete(2)".
  std::string describe() const;

  bool operator==(const Space& other) const = default;

 private:
  SpaceKind kind_ = SpaceKind::kBox;
  std::vector<int> shape_;
  std::vector<float> low_, high_;
  int64_t n_ = 0;
  int64_t start_ = 0;
  std::vector<int64_t> nvec_;
};

}  // namespace rlrun
