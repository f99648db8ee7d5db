#include "rlrun/tune/pruner.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

namespace rlrun::tune {
namespace {

bool maximize(const StudyView& study) { return study.direction == StudyDirection::kMaximize; }

// numpy.nanpercentile with linear interpolation (numpy's default method).
double nan_percentile(std::vector<double> values, double q) {
  values.erase(std::remove_if(values.begin(), values.end(), [](double v) { return std::isnan(v); }),
               values.end());
  if (values.empty()) return std::nan("");
  std::sort(values.begin(), values.end());
  const double position = q / 100.0 * static_cast<double>(values.size() - 1);
  const auto below = static_cast<size_t>(std::floor(position));
  const size_t above = std::min(below + 1, values.size() - 1);
  const double fraction = position - static_cast<double>(below);
  return values[below] + (values[above] - values[below]) * fraction;
}

// _percentile.py _is_first_in_interval_step: the trial's previous report was before the
// interval this step falls in.
bool first_in_interval(int64_t step, const FrozenTrial& trial, int64_t warmup, int64_t interval) {
  const int64_t nearest_lower = (step - warmup) / interval * interval + warmup;
  int64_t second_last = -1;
  for (const auto& [s, value] : trial.intermediate_values)
    if (s > second_last && s != step) second_last = s;
  return second_last < nearest_lower;
}

class PercentilePruner : public Pruner {
 public:
  PercentilePruner(const PrunerConfig& c, int64_t warmup)
      : percentile_(c.percentile),
        n_startup_trials_(c.n_startup_trials),
        n_warmup_steps_(warmup),
        interval_steps_(c.interval_steps),
        n_min_trials_(c.n_min_trials) {}

  bool prune(const StudyView& study, const FrozenTrial& trial, const SetSystemAttr&) override {
    std::vector<const FrozenTrial*> completed;
    for (const auto& t : study.trials)
      if (t.state == TrialState::kComplete) completed.push_back(&t);
    if (completed.empty() || static_cast<int>(completed.size()) < n_startup_trials_) return false;
    const auto step = trial.last_step();
    if (!step || *step < n_warmup_steps_) return false;
    if (!first_in_interval(*step, trial, n_warmup_steps_, interval_steps_)) return false;
    // The trial's best so far (nanmax / nanmin over its reports); all NaN prunes.
    double best = std::nan("");
    for (const auto& [s, v] : trial.intermediate_values) {
      if (std::isnan(v)) continue;
      if (std::isnan(best) || (maximize(study) ? v > best : v < best)) best = v;
    }
    if (std::isnan(best)) return true;
    std::vector<double> at_step;
    for (const FrozenTrial* t : completed) {
      auto it = t->intermediate_values.find(*step);
      if (it != t->intermediate_values.end()) at_step.push_back(it->second);
    }
    if (static_cast<int>(at_step.size()) < n_min_trials_) return false;
    const double p = nan_percentile(at_step, maximize(study) ? 100 - percentile_ : percentile_);
    if (std::isnan(p)) return false;
    return maximize(study) ? best < p : best > p;
  }

 private:
  double percentile_;
  int n_startup_trials_;
  int64_t n_warmup_steps_;
  int64_t interval_steps_;
  int n_min_trials_;
};

std::string rung_key(int rung) { return "completed_rung_" + std::to_string(rung); }

class SuccessiveHalvingPruner : public Pruner {
 public:
  explicit SuccessiveHalvingPruner(const PrunerConfig& c)
      : min_resource_(c.min_resource),
        reduction_factor_(c.reduction_factor),
        min_early_stopping_rate_(c.min_early_stopping_rate) {}

  bool prune(const StudyView& study, const FrozenTrial& trial,
             const SetSystemAttr& set_system_attr) override {
    const auto step = trial.last_step();
    if (!step) return false;
    int rung = 0;
    while (trial.system_attrs.contains(rung_key(rung))) ++rung;
    const double value = trial.intermediate_values.at(*step);
    for (;;) {
      if (!min_resource_) {
        min_resource_ = estimate_min_resource(study);
        if (!min_resource_) return false;
      }
      const double promotion_step =
          static_cast<double>(*min_resource_) *
          std::pow(static_cast<double>(reduction_factor_), min_early_stopping_rate_ + rung);
      if (static_cast<double>(*step) < promotion_step) return false;
      if (std::isnan(value)) return true;
      set_system_attr(rung_key(rung), value);
      // The values other trials recorded for this rung, and this one.
      std::vector<double> competing;
      for (const auto& t : study.trials) {
        if (t.trial_id == trial.trial_id) continue;
        auto it = t.system_attrs.find(rung_key(rung));
        if (it != t.system_attrs.end() && it->is_number()) competing.push_back(it->get<double>());
      }
      competing.push_back(value);
      if (!promotable(value, competing, maximize(study))) return true;
      ++rung;
    }
  }

 private:
  // _estimate_min_resource: the largest last step of a completed trial, / 100, at least 1.
  static std::optional<int64_t> estimate_min_resource(const StudyView& study) {
    std::optional<int64_t> last;
    for (const auto& t : study.trials)
      if (t.state == TrialState::kComplete && t.last_step())
        last = std::max(last.value_or(0), *t.last_step());
    if (!last) return std::nullopt;
    return std::max<int64_t>(*last / 100, 1);
  }

  // _is_trial_promotable_to_next_rung: in the top len // reduction_factor (at least the best).
  bool promotable(double value, std::vector<double> competing, bool maximizing) const {
    int64_t index = static_cast<int64_t>(competing.size()) / reduction_factor_ - 1;
    if (index < 0) index = 0;
    std::sort(competing.begin(), competing.end());
    if (maximizing) return value >= competing[competing.size() - 1 - static_cast<size_t>(index)];
    return value <= competing[static_cast<size_t>(index)];
  }

  std::optional<int64_t> min_resource_;
  int reduction_factor_;
  int min_early_stopping_rate_;
};

class NopPruner : public Pruner {
 public:
  bool prune(const StudyView&, const FrozenTrial&, const SetSystemAttr&) override { return false; }
};

}  // namespace

std::unique_ptr<Pruner> make_pruner(const PrunerConfig& config, int64_t default_warmup) {
  if (config.type == "none") return std::make_unique<NopPruner>();
  if (config.type == "successive_halving") return std::make_unique<SuccessiveHalvingPruner>(config);
  PrunerConfig c = config;
  if (config.type == "median") c.percentile = 50;
  return std::make_unique<PercentilePruner>(c, config.n_warmup_steps.value_or(default_warmup));
}

}  // namespace rlrun::tune
