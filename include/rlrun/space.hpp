#pragma once
// Gymnasium spaces (gymnasium/spaces/*.py) as one value type: Box, Discrete, MultiDiscrete,
// MultiBinary, and Dict of those (one level deep, as SB3's MultiInputPolicy takes them).
// A Box holds float32 or uint8 values (Gymnasium's Box dtype; uint8 is what SB3 calls an image
// and what its replay buffer stores as bytes). Every sample is a flat float32 vector: a Discrete value is one float holding the integer,
// MultiDiscrete / MultiBinary one float per entry, a Dict its keys' samples one after another
// in sorted key order (Gymnasium sorts a Dict's keys; SB3's CombinedExtractor concatenates
// them in that order). That keeps env I/O, buffers and networks on one data type.
//
// Part of the plugin API (header-only: plugins build their spaces with these functions).
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numeric>
#include <span>
#include <sstream>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "rlrun/rng.hpp"

namespace rlrun {

enum class SpaceKind : int32_t {
  kBox = 0,
  kDiscrete = 1,
  kMultiDiscrete = 2,
  kMultiBinary = 3,
  kDict = 4
};

// The element type of a Box (Gymnasium's Box(dtype=...)): float32, or uint8 for images.
// Samples are float32 either way; a uint8 Box holds whole numbers in its bounds (0-255 at most),
// which rlrun's buffers keep as bytes (SB3's buffers keep the space's dtype).
enum class BoxDtype : int32_t { kFloat32 = 0, kUint8 = 1 };

inline const char* box_dtype_name(BoxDtype dtype) {
  return dtype == BoxDtype::kUint8 ? "uint8" : "float32";
}

// "Box", "Discrete", ... as Gymnasium names the classes.
inline const char* space_kind_name(SpaceKind kind) {
  switch (kind) {
    case SpaceKind::kBox: return "Box";
    case SpaceKind::kDiscrete: return "Discrete";
    case SpaceKind::kMultiDiscrete: return "MultiDiscrete";
    case SpaceKind::kMultiBinary: return "MultiBinary";
    case SpaceKind::kDict: return "Dict";
  }
  return "?";
}

// The most values a Discrete space (or one entry of a MultiDiscrete) may have: every sample is
// a float32, which holds integers exactly up to 2^24, and a policy gives a Discrete action one
// output per value (SB3's Categorical) and a Discrete observation one input per value (one-hot).
inline constexpr int64_t kMaxDiscreteValues = int64_t{1} << 24;

class Space {
 public:
  Space() = default;

  // Box(low, high, shape, dtype): bounds per element (flattened, row-major like numpy). A uint8
  // Box's bounds are whole numbers from 0 to 255.
  static Space box(std::vector<float> low, std::vector<float> high, std::vector<int> shape = {},
                   BoxDtype dtype = BoxDtype::kFloat32) {
    if (shape.empty()) shape = {static_cast<int>(low.size())};
    if (low.size() != high.size() || static_cast<int64_t>(low.size()) != product(shape))
      throw std::invalid_argument("Space::box: low, high and shape sizes differ");
    for (size_t i = 0; i < low.size(); ++i)
      if (!(low[i] <= high[i])) throw std::invalid_argument("Space::box: low > high (or NaN)");
    if (dtype == BoxDtype::kUint8)
      for (size_t i = 0; i < low.size(); ++i)
        if (!is_byte_value(low[i]) || !is_byte_value(high[i]))
          throw std::invalid_argument(
              "Space::box: a uint8 Box's bounds are whole numbers from 0 to 255");
    Space s;
    s.kind_ = SpaceKind::kBox;
    s.low_ = std::move(low);
    s.high_ = std::move(high);
    s.shape_ = std::move(shape);
    s.dtype_ = dtype;
    return s;
  }
  // Box with the same bound for every element.
  static Space box(float low, float high, std::vector<int> shape,
                   BoxDtype dtype = BoxDtype::kFloat32) {
    const int64_t n = product(shape);
    if (n < 0) throw std::invalid_argument("Space::box: negative shape");
    return box(std::vector<float>(static_cast<size_t>(n), low),
               std::vector<float>(static_cast<size_t>(n), high), std::move(shape), dtype);
  }
  // An image as SB3's is_image_space wants it: Box(0, 255, shape, uint8).
  static Space image(std::vector<int> shape) {
    return box(0.0f, 255.0f, std::move(shape), BoxDtype::kUint8);
  }
  // Discrete(n, start): values start, ..., start + n - 1.
  static Space discrete(int64_t n, int64_t start = 0) {
    if (n <= 0) throw std::invalid_argument("Space::discrete: n must be positive");
    if (n > kMaxDiscreteValues || start < -kMaxDiscreteValues || start > kMaxDiscreteValues - n)
      throw std::invalid_argument(
          too_many_values("Discrete(" + std::to_string(n) +
                          (start ? ", start=" + std::to_string(start) : "") + ")"));
    Space s;
    s.kind_ = SpaceKind::kDiscrete;
    s.n_ = n;
    s.start_ = start;
    return s;
  }
  static Space multi_discrete(std::vector<int64_t> nvec) {
    if (nvec.empty()) throw std::invalid_argument("Space::multi_discrete: nvec is empty");
    for (auto n : nvec) {
      if (n <= 0) throw std::invalid_argument("Space::multi_discrete: entries must be positive");
      if (n > kMaxDiscreteValues)
        throw std::invalid_argument(
            too_many_values("a MultiDiscrete entry of " + std::to_string(n)));
    }
    Space s;
    s.kind_ = SpaceKind::kMultiDiscrete;
    s.shape_ = {static_cast<int>(nvec.size())};
    s.nvec_ = std::move(nvec);
    return s;
  }
  static Space multi_binary(int n) {
    if (n <= 0) throw std::invalid_argument("Space::multi_binary: n must be positive");
    Space s;
    s.kind_ = SpaceKind::kMultiBinary;
    s.shape_ = {n};
    s.n_ = n;
    return s;
  }
  // Dict of named subspaces (no Dict inside a Dict); keys are kept sorted.
  static Space dict(std::vector<std::pair<std::string, Space>> entries) {
    if (entries.empty()) throw std::invalid_argument("Space::dict: no keys");
    std::sort(entries.begin(), entries.end(),
              [](const auto& a, const auto& b) { return a.first < b.first; });
    Space s;
    s.kind_ = SpaceKind::kDict;
    for (size_t i = 0; i < entries.size(); ++i) {
      if (i > 0 && entries[i].first == entries[i - 1].first)
        throw std::invalid_argument("Space::dict: key '" + entries[i].first + "' twice");
      if (entries[i].second.kind_ == SpaceKind::kDict)
        throw std::invalid_argument("Space::dict: '" + entries[i].first +
                                    "' is a Dict; one level of keys is supported (as SB3)");
      s.keys_.push_back(std::move(entries[i].first));
      s.subspaces_.push_back(std::move(entries[i].second));
    }
    return s;
  }

  SpaceKind kind() const { return kind_; }
  bool is_box() const { return kind_ == SpaceKind::kBox; }
  bool is_discrete() const { return kind_ == SpaceKind::kDiscrete; }
  bool is_dict() const { return kind_ == SpaceKind::kDict; }
  // A Box's element type (float32 for every other kind).
  BoxDtype dtype() const { return dtype_; }
  bool is_uint8_box() const { return kind_ == SpaceKind::kBox && dtype_ == BoxDtype::kUint8; }

  // Number of floats in one flat sample (Discrete: 1; Dict: its keys' together).
  int flat_dim() const {
    switch (kind_) {
      case SpaceKind::kBox: return static_cast<int>(product(shape_));
      case SpaceKind::kDiscrete: return 1;
      case SpaceKind::kMultiDiscrete: return static_cast<int>(nvec_.size());
      case SpaceKind::kMultiBinary: return static_cast<int>(n_);
      case SpaceKind::kDict: {
        int total = 0;
        for (const Space& s : subspaces_) total += s.flat_dim();
        return total;
      }
    }
    return 0;
  }
  const std::vector<int>& shape() const { return shape_; }
  const std::vector<float>& low() const { return low_; }
  const std::vector<float>& high() const { return high_; }
  int64_t n() const { return n_; }
  int64_t start() const { return start_; }
  const std::vector<int64_t>& nvec() const { return nvec_; }
  // Dict: the keys in sorted order and their spaces.
  const std::vector<std::string>& keys() const { return keys_; }
  const std::vector<Space>& subspaces() const { return subspaces_; }
  // Dict: where key i's floats start in a flat sample.
  int offset(size_t i) const {
    int at = 0;
    for (size_t k = 0; k < i; ++k) at += subspaces_[k].flat_dim();
    return at;
  }

  bool contains(std::span<const float> x) const {
    if (static_cast<int64_t>(x.size()) != flat_dim()) return false;
    switch (kind_) {
      case SpaceKind::kBox:
        for (size_t i = 0; i < x.size(); ++i)
          if (!(x[i] >= low_[i] && x[i] <= high_[i])) return false;
        if (dtype_ == BoxDtype::kUint8)
          for (float v : x)
            if (v != std::floor(v)) return false;
        return true;
      case SpaceKind::kDiscrete: {
        const float v = x[0];
        return v == std::floor(v) && v >= static_cast<float>(start_) &&
               v < static_cast<float>(start_ + n_);
      }
      case SpaceKind::kMultiDiscrete:
        for (size_t i = 0; i < x.size(); ++i)
          if (!(x[i] == std::floor(x[i]) && x[i] >= 0 && x[i] < static_cast<float>(nvec_[i])))
            return false;
        return true;
      case SpaceKind::kMultiBinary:
        for (float v : x)
          if (v != 0.0f && v != 1.0f) return false;
        return true;
      case SpaceKind::kDict:
        for (size_t i = 0; i < subspaces_.size(); ++i)
          if (!subspaces_[i].contains(x.subspan(static_cast<size_t>(offset(i)),
                                                static_cast<size_t>(subspaces_[i].flat_dim()))))
            return false;
        return true;
    }
    return false;
  }

  // Uniform sample as gymnasium does (Box: uniform on bounded dims, shifted exponential on
  // half-bounded ones, normal on unbounded ones, gymnasium/spaces/box.py — a uint8 Box draws
  // floor(uniform(low, high + 1)), box.py's integer rule; Discrete: uniform integer; Dict: each
  // key in order).
  // `out` must hold exactly flat_dim() floats (a wrong size is refused: the bounds are read
  // index by index alongside it).
  void sample(Rng& rng, std::span<float> out) const {
    if (out.size() != static_cast<size_t>(flat_dim()))
      throw std::invalid_argument("Space::sample: " + std::to_string(out.size()) +
                                  " floats given for " + describe() + ", which has " +
                                  std::to_string(flat_dim()));
    switch (kind_) {
      case SpaceKind::kBox:
        if (dtype_ == BoxDtype::kUint8) {
          for (size_t i = 0; i < out.size(); ++i)
            out[i] = std::min(
                high_[i],
                static_cast<float>(std::floor(rng.uniform(low_[i], double{high_[i]} + 1.0))));
          return;
        }
        for (size_t i = 0; i < out.size(); ++i) {
          const bool lo = std::isfinite(low_[i]), hi = std::isfinite(high_[i]);
          if (lo && hi)
            out[i] = static_cast<float>(rng.uniform(low_[i], high_[i]));
          else if (lo)
            out[i] = static_cast<float>(low_[i] - std::log(1.0 - rng.uniform()));
          else if (hi)
            out[i] = static_cast<float>(high_[i] + std::log(1.0 - rng.uniform()));
          else
            out[i] = static_cast<float>(rng.normal());
        }
        return;
      case SpaceKind::kDiscrete:
        out[0] = static_cast<float>(start_ + static_cast<int64_t>(rng.below(n_)));
        return;
      case SpaceKind::kMultiDiscrete:
        for (size_t i = 0; i < out.size(); ++i) out[i] = static_cast<float>(rng.below(nvec_[i]));
        return;
      case SpaceKind::kMultiBinary:
        for (float& v : out) v = static_cast<float>(rng.below(2));
        return;
      case SpaceKind::kDict:
        for (size_t i = 0; i < subspaces_.size(); ++i)
          subspaces_[i].sample(rng, out.subspan(static_cast<size_t>(offset(i)),
                                                static_cast<size_t>(subspaces_[i].flat_dim())));
        return;
    }
  }

  // Readable form as Gymnasium's repr, e.g. "Box(-2.0, 2.0, (1,), float32)", "Discrete(2)",
  // "Dict('goal': Box(...), 'position': Box(...))".
  std::string describe() const {
    std::ostringstream out;
    switch (kind_) {
      case SpaceKind::kBox:
        if (all_equal(low_) && all_equal(high_)) {
          out << "Box(" << bound_text(low_.front()) << ", " << bound_text(high_.front()) << ", "
              << shape_text() << ", " << box_dtype_name(dtype_) << ")";
        } else {
          out << "Box([";
          for (size_t i = 0; i < low_.size(); ++i) out << (i ? " " : "") << bound_text(low_[i]);
          out << "], [";
          for (size_t i = 0; i < high_.size(); ++i) out << (i ? " " : "") << bound_text(high_[i]);
          out << "], " << shape_text() << ", " << box_dtype_name(dtype_) << ")";
        }
        break;
      case SpaceKind::kDiscrete:
        out << "Discrete(" << n_;
        if (start_ != 0) out << ", start=" << start_;
        out << ")";
        break;
      case SpaceKind::kMultiDiscrete:
        out << "MultiDiscrete([";
        for (size_t i = 0; i < nvec_.size(); ++i) out << (i ? " " : "") << nvec_[i];
        out << "])";
        break;
      case SpaceKind::kMultiBinary: out << "MultiBinary(" << n_ << ")"; break;
      case SpaceKind::kDict:
        out << "Dict(";
        for (size_t i = 0; i < keys_.size(); ++i)
          out << (i ? ", " : "") << "'" << keys_[i] << "': " << subspaces_[i].describe();
        out << ")";
        break;
    }
    return out.str();
  }

  bool operator==(const Space& other) const = default;

  // Why a Discrete space this large cannot be learnt here.
  static std::string too_many_values(const std::string& what) {
    return what +
           " has too many values: rlrun gives a Discrete action one policy output per "
           "value and a Discrete observation a one-hot input of that many floats, and holds the "
           "value in a float32; at most " +
           std::to_string(kMaxDiscreteValues) + " (2^24) values, from -2^24 to 2^24";
  }

 private:
  static int64_t product(const std::vector<int>& shape) {
    int64_t n = 1;
    for (int d : shape) n *= d;
    return n;
  }
  static bool is_byte_value(float v) { return v >= 0.0f && v <= 255.0f && v == std::floor(v); }
  // numpy prints a uint8 bound as "255", a float32 one as "255.0".
  std::string bound_text(float v) const {
    return dtype_ == BoxDtype::kUint8 ? std::to_string(static_cast<int>(v)) : format_bound(v);
  }
  static std::string format_bound(float v) {
    if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
    std::ostringstream out;
    out << v;
    std::string s = out.str();
    if (s.find_first_of(".e") == std::string::npos) s += ".0";
    return s;
  }
  static bool all_equal(const std::vector<float>& v) {
    for (float x : v)
      if (!(x == v.front())) return false;
    return true;
  }
  std::string shape_text() const {
    std::string s = "(";
    // Python's tuple repr: (3,) for one dimension, (84, 84, 3) for more.
    for (size_t i = 0; i < shape_.size(); ++i) s += (i ? ", " : "") + std::to_string(shape_[i]);
    if (shape_.size() == 1) s += ",";
    return s + ")";
  }

  SpaceKind kind_ = SpaceKind::kBox;
  std::vector<int> shape_;
  std::vector<float> low_, high_;
  BoxDtype dtype_ = BoxDtype::kFloat32;
  int64_t n_ = 0;
  int64_t start_ = 0;
  std::vector<int64_t> nvec_;
  std::vector<std::string> keys_;
  std::vector<Space> subspaces_;
};

}  // namespace rlrun
