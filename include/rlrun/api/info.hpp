#pragma once
// Numeric per-step info of a plugin env: Gymnasium's `info` dict restricted to numbers.
// Declare every key in the env's constructor (add_key returns its index); then reset() and
// step() call clear() and set() the values of that step. A key whose value is absent this
// step is NaN. rlrun reads two keys by name: `is_success` (success rate in evaluations and
// the Monitor's is_success column, as SB3) and, by convention, `is_failure`.
#include <cmath>
#include <limits>
#include <string>
#include <string_view>
#include <vector>

namespace rlrun::api {

class Info {
 public:
  // Declares a key (idempotent) and returns its index for set().
  int add_key(std::string_view name) {
    for (size_t i = 0; i < keys_.size(); ++i)
      if (keys_[i] == name) return static_cast<int>(i);
    keys_.emplace_back(name);
    values_.push_back(kAbsent);
    return static_cast<int>(keys_.size() - 1);
  }
  void set(int index, double value) { values_[static_cast<size_t>(index)] = value; }
  double get(int index) const { return values_[static_cast<size_t>(index)]; }
  // Marks every value absent; call it at the start of reset() and step().
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

}  // namespace rlrun::api
