#include "rlrun/tune/observation_pairs.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

namespace rlrun::tune {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// numpy sorts NaN after every number; a strict weak order with that rule.
bool less_nan_last(double a, double b) {
  if (std::isnan(a)) return false;
  if (std::isnan(b)) return true;
  return a < b;
}

}  // namespace

ObservationPairs get_observation_pairs(const StudyView& study, const SearchSpace& space) {
  const double sign = study.direction == StudyDirection::kMaximize ? -1.0 : 1.0;
  ObservationPairs out;
  for (const auto& [name, distribution] : space) out.values[name];
  for (const FrozenTrial& trial : study.trials) {
    RankKey key;
    if (trial.state == TrialState::kComplete) {
      const auto value = trial.value();
      if (!value) continue;
      key = {-kInf, sign * *value};
    } else if (trial.state == TrialState::kPruned) {
      if (const auto step = trial.last_step()) {
        const double reported = trial.intermediate_values.at(*step);
        key = {-static_cast<double>(*step), std::isnan(reported) ? kInf : sign * reported};
      } else {
        key = {1.0, 0.0};
      }
    } else {
      continue;
    }
    out.keys.push_back(key);
    for (const auto& [name, distribution] : space) {
      double value = kNaN;
      const auto param = trial.params.find(name);
      const auto asked = trial.distributions.find(name);
      if (param != trial.params.end() && asked != trial.distributions.end() &&
          compatible(asked->second, distribution) &&
          !(is_log_scale(distribution) && !(param->second > 0)) &&
          !(std::holds_alternative<CategoricalDistribution>(distribution) &&
            !contains(distribution, param->second)))
        value = param->second;
      out.values[name].push_back(value);
    }
  }
  return out;
}

BelowAbove split_observation_pairs(const std::vector<RankKey>& keys, int n_below) {
  std::vector<size_t> order(keys.size());
  std::iota(order.begin(), order.end(), size_t{0});
  std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) {
    if (less_nan_last(keys[a].step, keys[b].step)) return true;
    if (less_nan_last(keys[b].step, keys[a].step)) return false;
    return less_nan_last(keys[a].score, keys[b].score);
  });
  const size_t cut = std::min(order.size(), static_cast<size_t>(std::max(n_below, 0)));
  BelowAbove out;
  out.below.assign(order.begin(), order.begin() + static_cast<std::ptrdiff_t>(cut));
  out.above.assign(order.begin() + static_cast<std::ptrdiff_t>(cut), order.end());
  // Back to trial order (np.sort of the indices).
  std::sort(out.below.begin(), out.below.end());
  std::sort(out.above.begin(), out.above.end());
  return out;
}

}  // namespace rlrun::tune
