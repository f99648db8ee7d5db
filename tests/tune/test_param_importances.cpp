// param_importances (src/rlrun/tune/study_report.hpp): Optuna's get_param_importances with its
// default fANOVA evaluator, on studies whose answer is known, against Optuna's own numbers.
#include <catch2/catch.hpp>

#include <cmath>
#include <map>

#include "rlrun/tune/study_report.hpp"
#include "tune/synthetic_study.hpp"

using rlrun::tune::FrozenTrial;
using rlrun::tune::param_importances;
using rlrun::tune::TrialState;
namespace synthetic = rlrun::tune::testing;

namespace {

std::vector<std::string> ranking(const std::vector<std::pair<std::string, double>>& importances) {
  std::vector<std::string> names;
  for (const auto& [name, importance] : importances) names.push_back(name);
  return names;
}

std::map<std::string, double> as_map(
    const std::vector<std::pair<std::string, double>>& importances) {
  return {importances.begin(), importances.end()};
}

double sum(const std::vector<std::pair<std::string, double>>& importances) {
  double s = 0;
  for (const auto& [name, importance] : importances) s += importance;
  return s;
}

// Optuna 3.1's get_param_importances(study, evaluator=FanovaImportanceEvaluator(seed=s)) for the
// same trials, from `/usr/bin/python3 tests/tune/optuna_importances.py 0 1 2 3 4` (Debian's
// python3-optuna 3.1.0 and python3-sklearn 1.2.1): the mean over its five seeds, and a tolerance
// that holds its spread over those seeds plus the difference our random numbers make.
struct OptunaImportances {
  std::map<std::string, double> mean;
  double tolerance;
};

void check_against_optuna(const std::vector<FrozenTrial>& trials,
                          const std::vector<std::string>& optuna_ranking,
                          const OptunaImportances& optuna) {
  const auto importances = param_importances(trials, 0);
  CHECK(ranking(importances) == optuna_ranking);
  CHECK(sum(importances) == Approx(1.0));
  for (const auto& [name, value] : as_map(importances)) {
    INFO(name);
    CHECK(value == Approx(optuna.mean.at(name)).margin(optuna.tolerance));
  }
}

}  // namespace

TEST_CASE("Importances: y depending on x1 alone puts x1 above 0.9, as Optuna", "[tune]") {
  check_against_optuna(synthetic::synthetic_study(synthetic::x1_only), {"x1", "x2", "x3"},
                       {{{"x1", 0.99923}, {"x2", 0.00050}, {"x3", 0.00028}}, 0.01});
  CHECK(as_map(param_importances(synthetic::synthetic_study(synthetic::x1_only)))["x1"] > 0.9);
}

TEST_CASE("Importances: y = x1 + 0.3 x2 ranks x1, x2, x3 as Optuna", "[tune]") {
  check_against_optuna(synthetic::synthetic_study(synthetic::x1_then_x2), {"x1", "x2", "x3"},
                       {{{"x1", 0.95851}, {"x2", 0.04079}, {"x3", 0.00070}}, 0.02});
}

TEST_CASE("Importances: a categorical parameter that matters, as Optuna", "[tune]") {
  // Its one-hot columns' variances count together as one parameter's.
  check_against_optuna(synthetic::synthetic_study(synthetic::categorical), {"optimizer", "x"},
                       {{{"optimizer", 0.99368}, {"x", 0.00632}}, 0.01});
}

TEST_CASE("Importances: log parameters, as Optuna", "[tune]") {
  check_against_optuna(
      synthetic::synthetic_study(synthetic::log_params), {"learning_rate", "gamma", "n_epochs"},
      {{{"learning_rate", 0.95991}, {"gamma", 0.03740}, {"n_epochs", 0.00269}}, 0.03});
}

TEST_CASE("Importances: a log parameter's volume is measured in its own units, as Optuna",
          "[tune]") {
  // Most trials have learning rates below 3e-4, where y is 1 higher; in Optuna's measure that is
  // 0.3 % of the range, so x's slope matters more (log space would say the opposite).
  check_against_optuna(synthetic::synthetic_study(synthetic::log_raw_space), {"x", "learning_rate"},
                       {{{"x", 0.70942}, {"learning_rate", 0.29058}}, 0.03});
}

TEST_CASE("Importances use COMPLETE trials and the parameters all of them share", "[tune]") {
  std::vector<FrozenTrial> trials = synthetic::synthetic_study(synthetic::x1_then_x2, 60);
  // A parameter of one possible value comes last with 0 (fANOVA leaves it out).
  for (FrozenTrial& t : trials) {
    t.distributions["fixed"] = rlrun::tune::FloatDistribution{2.0, 2.0, false, std::nullopt};
    t.params["fixed"] = 2.0;
  }
  // A parameter one trial lacks is not assessed; pruned, failed and infinite trials count not.
  trials[5].distributions["sometimes"] = rlrun::tune::FloatDistribution{0, 1, false, std::nullopt};
  trials[5].params["sometimes"] = 0.5;
  trials[7].state = TrialState::kPruned;
  trials[7].values.reset();
  trials[8].state = TrialState::kFail;
  trials[8].values.reset();
  trials[9].values = std::vector<double>{INFINITY};
  const auto importances = param_importances(trials, 0);
  CHECK(ranking(importances) == std::vector<std::string>{"x1", "x2", "x3", "fixed"});
  CHECK(importances.back().second == 0.0);
  CHECK(sum(importances) == Approx(1.0));
  // A different value for a pruned trial changes nothing.
  std::vector<FrozenTrial> changed = trials;
  changed[7].intermediate_values[3] = 1e6;
  CHECK(param_importances(changed, 0) == importances);
  // Seeds give different forests, the same ranking.
  CHECK(ranking(param_importances(trials, 99)) == ranking(importances));
}

TEST_CASE("Importances are empty when they cannot be assessed", "[tune]") {
  CHECK(param_importances({}).empty());
  CHECK(param_importances(synthetic::synthetic_study(synthetic::x1_only, 1)).empty());
  // Every value the same: no tree has variance (Optuna raises).
  std::vector<FrozenTrial> flat = synthetic::synthetic_study(synthetic::x1_only, 20);
  for (FrozenTrial& t : flat) t.values = std::vector<double>{1.0};
  CHECK(param_importances(flat).empty());
  // No parameter varies.
  std::vector<FrozenTrial> fixed = synthetic::synthetic_study(synthetic::x1_only, 20);
  for (FrozenTrial& t : fixed) {
    t.distributions = {{"a", rlrun::tune::IntDistribution{3, 3, false, 1}}};
    t.params = {{"a", 3.0}};
  }
  CHECK(param_importances(fixed).empty());
}
