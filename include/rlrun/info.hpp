#pragma once
// Numeric per-step info (Gymnasium's `info` dict restricted to numbers, e.g. `is_success`).
// Keys are declared once when the env is built, so step() only writes values and never
// allocates. A value that is absent this step is NaN.
#include <cmath>
#include <limits>
#include <string>
#include <string_view>
#include <vector>

namespace rlrun {

class Info {
 public:
  // Declares a key (idempotent) and returns its index for fast set()/get().
  int add_key(std::string_view name) {
    for (size_t i = 0; i < keys_.size(); ++i)
      if (keys_[i] == name) return static_cast<int>(i);
    keys_.emplace_back(name);
    values_.push_back(kAbsent);
    return static_cast<int>(keys_.size() - 1);
  }
  // Index of a key, or -1 if the env never declared it.
  int find(std::string_view name) const {
    for (size_t i = 0; i < keys_.size(); ++i)
      if (keys_[i] == name) return static_cast<int>(i);
    return -1;
  }
  void set(int index, double value) { values_[index] = value; }
  double get(int index) const { return values_[index]; }
  bool has(int index) const { return index >= 0 && !std::isnan(values_[index]); }
  // Marks every value absent; envs call it at the start of step() and reset().
  void clear() {
    for (auto& v : values_) v = kAbsent;
  }
  const std::vector<std::string>& keys() const { return keys_; }
  const std::vector<double>& values() const { return values_; }

  static constexpr double kAbsent = std::numeric_limits<double>::quiet_NaN();

 private:
  std::vector<std::string> keys_;
  std::vector<double> values_;
};

}  // namespace rlrun
