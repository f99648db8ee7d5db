// print_study_report (study_report.hpp): what `optuna` users look at after a study — the
// counts by state, study.best_trial (storages/_base.py get_best_trial: the first trial with the
// best value), the best trials (study.trials_dataframe() sorted by value), get_param_importances
// and plot_optimization_history — as plain text.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iomanip>
#include <sstream>

#include "rlrun/core/float_format.hpp"
#include "rlrun/core/plural.hpp"
#include "rlrun/tune/study_report.hpp"

namespace rlrun::tune {
namespace {

constexpr size_t kLineWidth = 100;  // the params column wraps to stay within it
constexpr int kBarWidth = 40;       // '#'s of an importance of 1

const char* direction_name(StudyDirection d) {
  switch (d) {
    case StudyDirection::kMaximize: return "maximize";
    case StudyDirection::kMinimize: return "minimize";
    default: return "direction not set";
  }
}

// A value as the table shows it: six significant digits.
std::string short_value(double v) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.6g", v);
  return buffer;
}

// A parameter's external value: strings bare, numbers as JSON writes them (shortest text).
std::string param_text(const FrozenTrial& trial, const std::string& name) {
  const nlohmann::json v = trial.param(name);
  return v.is_string() ? v.get<std::string>() : v.dump();
}

// "name=value" for each parameter, by name.
std::vector<std::string> param_items(const FrozenTrial& trial) {
  std::vector<std::string> items;
  for (const auto& [name, internal] : trial.params)
    items.push_back(name + "=" + param_text(trial, name));
  return items;
}

// The items joined with ", " after `prefix`; a line that would pass kLineWidth continues on the
// next, indented like the first item.
void wrapped(std::ostream& out, const std::string& prefix, const std::vector<std::string>& items) {
  std::string line = prefix;
  bool first = true;
  for (const std::string& item : items) {
    const std::string piece = first ? item : ", " + item;
    if (!first && line.size() + piece.size() > kLineWidth) {
      out << line << ",\n";
      line = std::string(prefix.size(), ' ') + item;
    } else {
      line += piece;
    }
    first = false;
  }
  out << line << '\n';
}

bool better(StudyDirection d, double a, double b) {
  return d == StudyDirection::kMaximize ? a > b : a < b;
}

// "N trials: COMPLETE a, PRUNED b, ..." in Optuna's state order.
void print_state_counts(const std::vector<FrozenTrial>& trials, std::ostream& out) {
  int counts[5] = {0, 0, 0, 0, 0};
  for (const FrozenTrial& t : trials)
    if (static_cast<int>(t.state) >= 0 && static_cast<int>(t.state) < 5)
      ++counts[static_cast<int>(t.state)];
  out << count_of(static_cast<int64_t>(trials.size()), "trial") << ":";
  const TrialState order[] = {TrialState::kComplete, TrialState::kPruned, TrialState::kFail,
                              TrialState::kRunning, TrialState::kWaiting};
  for (TrialState s : order)
    out << (s == TrialState::kComplete ? " " : ", ") << state_name(s) << ' '
        << counts[static_cast<int>(s)];
  out << "\n\n";
}

// The complete trials, best first; equal values by number (Python's max/min and sorted keep
// the first). A NaN value (which Optuna never stores as COMPLETE) goes last.
std::vector<const FrozenTrial*> ranked_complete(const std::vector<FrozenTrial>& trials,
                                                StudyDirection direction) {
  std::vector<const FrozenTrial*> ranked;
  for (const FrozenTrial& t : trials)
    if (t.state == TrialState::kComplete && t.value()) ranked.push_back(&t);
  std::stable_sort(ranked.begin(), ranked.end(), [&](const FrozenTrial* a, const FrozenTrial* b) {
    const double va = *a->value(), vb = *b->value();
    if (std::isnan(va) || std::isnan(vb)) return !std::isnan(va) && std::isnan(vb);
    return better(direction, va, vb);
  });
  return ranked;
}

void print_best(const std::vector<const FrozenTrial*>& ranked, std::ostream& out) {
  if (ranked.empty()) {
    out << "best trial: none (no trial is complete)\n";
    return;
  }
  const FrozenTrial& best = *ranked.front();
  out << "best trial: " << best.number << ", value " << python_float_repr(*best.value()) << '\n';
  wrapped(out, "  params:     ", param_items(best));
  if (!best.user_attrs.empty()) {
    std::vector<std::string> attrs;
    for (const auto& [key, value] : best.user_attrs.items())
      attrs.push_back(key + "=" + value.dump());
    wrapped(out, "  user attrs: ", attrs);
  }
}

void print_top(const std::vector<const FrozenTrial*>& ranked, int top, std::ostream& out) {
  if (ranked.empty() || top <= 0) return;
  const size_t shown = std::min(ranked.size(), static_cast<size_t>(top));
  out << "\ntop " << shown << " of "
      << count_of(static_cast<int64_t>(ranked.size()), "complete trial") << ":\n";
  size_t value_width = 5;
  for (size_t i = 0; i < shown; ++i)
    value_width = std::max(value_width, short_value(*ranked[i]->value()).size());
  std::ostringstream header;
  header << "  " << std::setw(6) << "trial"
         << "  " << std::left << std::setw(static_cast<int>(value_width)) << "value"
         << "  params";
  out << header.str() << '\n';
  for (size_t i = 0; i < shown; ++i) {
    std::ostringstream prefix;
    prefix << "  " << std::setw(6) << ranked[i]->number << "  " << std::left
           << std::setw(static_cast<int>(value_width)) << short_value(*ranked[i]->value()) << "  ";
    wrapped(out, prefix.str(), param_items(*ranked[i]));
  }
}

void print_importances(const std::vector<FrozenTrial>& trials, uint64_t seed, std::ostream& out) {
  out << "\nparameter importances (fANOVA, Optuna's default evaluator):\n";
  const auto importances = param_importances(trials, seed);
  if (importances.empty()) {
    out << "  none: they need two complete trials with finite, different values and a parameter "
           "that varies\n";
    return;
  }
  size_t name_width = 0;
  for (const auto& [param, importance] : importances)
    name_width = std::max(name_width, param.size());
  for (const auto& [param, importance] : importances) {
    char number[16];
    std::snprintf(number, sizeof number, "%.3f", importance);
    out << "  " << std::left << std::setw(static_cast<int>(name_width)) << param << std::right
        << "  " << number << "  "
        << std::string(static_cast<size_t>(std::lround(importance * kBarWidth)), '#') << '\n';
  }
}

}  // namespace

void print_study_report(const std::string& name, StudyDirection direction,
                        const std::vector<FrozenTrial>& trials, const ReportOptions& options,
                        std::ostream& out) {
  out << "study " << name << " (" << direction_name(direction) << ")\n";
  print_state_counts(trials, out);
  const std::vector<const FrozenTrial*> ranked = ranked_complete(trials, direction);
  print_best(ranked, out);
  print_top(ranked, options.top, out);
  print_importances(trials, options.seed, out);
  if (!options.plot_path.empty()) {
    write_history_plot(name, direction, trials, options.plot_path, options.plot_pruned);
    out << "\nhistory plot: " << options.plot_path
        << (ranked.empty() ? " (empty: no complete trial)" : "") << '\n';
  }
}

}  // namespace rlrun::tune
