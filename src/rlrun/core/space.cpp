#include "rlrun/core/space.hpp"

#include <cmath>
#include <limits>
#include <numeric>
#include <sstream>
#include <stdexcept>

namespace rlrun {

namespace {

int product(const std::vector<int>& shape) {
  return std::accumulate(shape.begin(), shape.end(), 1, std::multiplies<int>());
}

std::string format_bound(float v) {
  if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
  std::ostringstream out;
  out << v;
  std::string s = out.str();
  if (s.find_first_of(".e") == std::string::npos) s += ".0";
  return s;
}

bool all_equal(const std::vector<float>& v) {
  for (float x : v)
    if (!(x == v.front())) return false;
  return true;
}

}  // namespace

Space Space::box(std::vector<float> low, std::vector<float> high, std::vector<int> shape) {
  if (shape.empty()) shape = {static_cast<int>(low.size())};
  if (low.size() != high.size() || static_cast<int>(low.size()) != product(shape))
    throw std::invalid_argument("Space::box: low, high and shape sizes differ");
  for (size_t i = 0; i < low.size(); ++i)
    if (low[i] > high[i]) throw std::invalid_argument("Space::box: low > high");
  Space s;
  s.kind_ = SpaceKind::kBox;
  s.low_ = std::move(low);
  s.high_ = std::move(high);
  s.shape_ = std::move(shape);
  return s;
}

Space Space::box(float low, float high, std::vector<int> shape) {
  const int n = product(shape);
  return box(std::vector<float>(n, low), std::vector<float>(n, high), std::move(shape));
}

Space Space::discrete(int64_t n, int64_t start) {
  if (n <= 0) throw std::invalid_argument("Space::discrete: n must be positive");
  Space s;
  s.kind_ = SpaceKind::kDiscrete;
  s.n_ = n;
  s.start_ = start;
  s.shape_ = {};
  return s;
}

Space Space::multi_discrete(std::vector<int64_t> nvec) {
  for (auto n : nvec)
    if (n <= 0) throw std::invalid_argument("Space::multi_discrete: entries must be positive");
  Space s;
  s.kind_ = SpaceKind::kMultiDiscrete;
  s.shape_ = {static_cast<int>(nvec.size())};
  s.nvec_ = std::move(nvec);
  return s;
}

Space Space::multi_binary(int n) {
  if (n <= 0) throw std::invalid_argument("Space::multi_binary: n must be positive");
  Space s;
  s.kind_ = SpaceKind::kMultiBinary;
  s.shape_ = {n};
  s.n_ = n;
  return s;
}

int Space::flat_dim() const {
  switch (kind_) {
    case SpaceKind::kBox: return product(shape_);
    case SpaceKind::kDiscrete: return 1;
    case SpaceKind::kMultiDiscrete: return static_cast<int>(nvec_.size());
    case SpaceKind::kMultiBinary: return static_cast<int>(n_);
  }
  return 0;
}

bool Space::contains(std::span<const float> x) const {
  if (static_cast<int>(x.size()) != flat_dim()) return false;
  switch (kind_) {
    case SpaceKind::kBox:
      for (size_t i = 0; i < x.size(); ++i)
        if (!(x[i] >= low_[i] && x[i] <= high_[i])) return false;
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
  }
  return false;
}

void Space::sample(Rng& rng, std::span<float> out) const {
  switch (kind_) {
    case SpaceKind::kBox:
      // gymnasium/spaces/box.py: uniform if bounded, shifted exponential if half-bounded,
      // normal if unbounded.
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
  }
}

std::string Space::describe() const {
  std::ostringstream out;
  auto shape_str = [&] {
    std::string s = "(";
    for (size_t i = 0; i < shape_.size(); ++i) s += std::to_string(shape_[i]) + ",";
    if (shape_.size() > 1) s.pop_back();
    return s + ")";
  };
  switch (kind_) {
    case SpaceKind::kBox:
      if (all_equal(low_) && all_equal(high_)) {
        out << "Box(" << format_bound(low_.front()) << ", " << format_bound(high_.front())
            << ", " << shape_str() << ", float32)";
      } else {
        out << "Box([";
        for (size_t i = 0; i < low_.size(); ++i) out << (i ? " " : "") << format_bound(low_[i]);
        out << "], [";
        for (size_t i = 0; i < high_.size(); ++i) out << (i ? " " : "") << format_bound(high_[i]);
        out << "], " << shape_str() << ", float32)";
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
  }
  return out.str();
}

}  // namespace rlrun
