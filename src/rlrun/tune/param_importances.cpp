// param_importances (study_report.hpp): Optuna 3.1's get_param_importances(study) with its
// default evaluator (optuna/importance/__init__.py, _base.py, _fanova/_evaluator.py).
#include <algorithm>
#include <cmath>
#include <map>
#include <variant>

#include "rlrun/tune/fanova.hpp"
#include "rlrun/tune/study_report.hpp"

namespace rlrun::tune {
namespace {

// intersection_search_space(study, ordered_dict=True): the parameters every COMPLETE trial has,
// with the same distribution in all of them, by name.
std::map<std::string, Distribution> intersection_search_space(
    const std::vector<const FrozenTrial*>& complete) {
  std::map<std::string, Distribution> space = complete.front()->distributions;
  for (const FrozenTrial* t : complete)
    std::erase_if(space, [&](const auto& entry) {
      const auto it = t->distributions.find(entry.first);
      return it == t->distributions.end() || !(it->second == entry.second);
    });
  return space;
}

}  // namespace

std::vector<std::pair<std::string, double>> param_importances(
    const std::vector<FrozenTrial>& trials, uint64_t seed) {
  std::vector<const FrozenTrial*> complete;
  for (const FrozenTrial& t : trials)
    if (t.state == TrialState::kComplete) complete.push_back(&t);
  if (complete.size() < 2) return {};  // Optuna raises ValueError here
  const std::map<std::string, Distribution> space = intersection_search_space(complete);

  // fANOVA does not take parameters of one possible value: they come last with importance 0.
  std::vector<std::string> varying, fixed;
  for (const auto& [name, distribution] : space)
    (single(distribution) ? fixed : varying).push_back(name);
  if (varying.empty()) return {};

  // _get_filtered_trials: a finite value (every COMPLETE trial has the parameters here).
  std::vector<const FrozenTrial*> used;
  for (const FrozenTrial* t : complete)
    if (t->value() && std::isfinite(*t->value())) used.push_back(t);
  if (used.size() < 2) return {};

  // _SearchSpaceTransform(transform_log=False, transform_step=False): numbers as they are —
  // log parameters too, and their bounds are low and high; a categorical parameter is one
  // column per choice (one-hot), each in [0, 1].
  std::vector<std::pair<double, double>> bounds;
  std::vector<std::vector<int>> groups;
  for (const std::string& name : varying) {
    std::vector<int> group;
    const Distribution& d = space.at(name);
    if (const auto* c = std::get_if<CategoricalDistribution>(&d)) {
      for (size_t i = 0; i < c->choices.size(); ++i) {
        group.push_back(static_cast<int>(bounds.size()));
        bounds.emplace_back(0.0, 1.0);
      }
    } else if (const auto* f = std::get_if<FloatDistribution>(&d)) {
      group.push_back(static_cast<int>(bounds.size()));
      bounds.emplace_back(f->low, f->high);
    } else {
      const auto& i = std::get<IntDistribution>(d);
      group.push_back(static_cast<int>(bounds.size()));
      bounds.emplace_back(static_cast<double>(i.low), static_cast<double>(i.high));
    }
    groups.push_back(std::move(group));
  }
  Eigen::MatrixXd x = Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(bounds.size()),
                                            static_cast<Eigen::Index>(used.size()));
  Eigen::VectorXd y(static_cast<Eigen::Index>(used.size()));
  for (size_t s = 0; s < used.size(); ++s) {
    const auto column = static_cast<Eigen::Index>(s);
    y(column) = *used[s]->value();
    for (size_t p = 0; p < varying.size(); ++p) {
      const double internal = used[s]->params.at(varying[p]);
      if (std::holds_alternative<CategoricalDistribution>(space.at(varying[p])))
        x(groups[p].at(static_cast<size_t>(internal)), column) = 1.0;
      else
        x(groups[p][0], column) = internal;
    }
  }

  FanovaConfig config;
  config.seed = seed;
  const auto raw = fanova_importances(x, y, bounds, groups, config);
  if (!raw) return {};  // every tree constant: all values equal (Optuna raises RuntimeError)
  double sum = 0;
  for (double v : *raw) sum += v;
  // Normalised to sum to one. A zero sum (the parameters act only together, say y = x1 xor
  // x2) gives every parameter an equal share, as get_param_importances does for a zero sum;
  // Optuna's evaluator divides by it first and returns NaNs.
  std::vector<std::pair<std::string, double>> out;
  for (size_t p = 0; p < varying.size(); ++p)
    out.emplace_back(varying[p],
                     sum > 0 ? (*raw)[p] / sum : 1.0 / static_cast<double>(varying.size()));
  for (const std::string& name : fixed) out.emplace_back(name, 0.0);
  // _sort_dict_by_importance: reversed(sorted(..., key=importance)), ties in reverse order.
  std::stable_sort(out.begin(), out.end(),
                   [](const auto& a, const auto& b) { return a.second < b.second; });
  std::reverse(out.begin(), out.end());
  return out;
}

}  // namespace rlrun::tune
