#pragma once
// Pruners as Optuna 3.1's (optuna/pruners/): after a trial reports an intermediate value, the
// pruner decides whether the trial stops early.
//   median / percentile: PercentilePruner (_percentile.py; MedianPruner is percentile 50):
//     no pruning until n_startup_trials trials COMPLETE, nor before step n_warmup_steps, and
//     only at the first report of each interval_steps interval; then the trial's best value so
//     far is compared with the percentile of the completed trials' values at this step.
//   successive_halving: SuccessiveHalvingPruner (_successive_halving.py, asynchronous SHA):
//     rung r is reached at step min_resource * reduction_factor^(min_early_stopping_rate + r);
//     the value there is recorded in the trial's system attribute completed_rung_<r>, and the
//     trial continues only when it is in the top 1/reduction_factor of the values recorded for
//     that rung so far. min_resource "auto": the largest last step of a completed trial / 100.
//   none: never prunes (NopPruner).
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>

#include <nlohmann/json.hpp>

#include "rlrun/core/config_checks.hpp"
#include "rlrun/tune/frozen_trial.hpp"

namespace rlrun::tune {

// The study file's `pruner:` section.
struct PrunerConfig {
  std::string type = "median";            // median | percentile | successive_halving | none
  double percentile = 50;                 // percentile: keep trials above this percentile
  int n_startup_trials = 5;               // median/percentile: completed trials before pruning
  std::optional<int64_t> n_warmup_steps;  // median/percentile: steps before pruning (null: the
                                          // zoo's n_evaluations / 3 per seed)
  int64_t interval_steps = 1;             // median/percentile: prune at most once per interval
  int n_min_trials = 1;                   // median/percentile: values needed at a step to compare
  std::optional<int64_t> min_resource;    // successive_halving: null = Optuna's "auto"
  int reduction_factor = 4;               // successive_halving
  int min_early_stopping_rate = 0;        // successive_halving

  template <class V>
  void visit(V& v) {
    v("type", type, "median, percentile, successive_halving or none (Optuna's pruners)",
      OneOf{{"median", "percentile", "successive_halving", "none"}});
    v("percentile", percentile, "percentile pruner: prune below this percentile (median: 50)",
      in_range(0, 100));
    v("n_startup_trials", n_startup_trials, "median/percentile: completed trials before pruning",
      non_negative());
    v("n_warmup_steps", n_warmup_steps,
      "median/percentile: reports before pruning starts (null: the zoo's n_evaluations // 3)",
      non_negative());
    v("interval_steps", interval_steps, "median/percentile: steps between pruning checks",
      at_least(1));
    v("n_min_trials", n_min_trials, "median/percentile: values at a step needed to compare",
      at_least(1));
    v("min_resource", min_resource,
      "successive_halving: steps before the first rung (null: Optuna's 'auto')", at_least(1));
    v("reduction_factor", reduction_factor, "successive_halving: keep the top 1/this per rung",
      at_least(2));
    v("min_early_stopping_rate", min_early_stopping_rate,
      "successive_halving: rungs skipped before the first comparison", non_negative());
  }
};

// Writes a system attribute of the trial being judged (successive halving's rungs).
using SetSystemAttr = std::function<void(const std::string& key, const nlohmann::json& value)>;

class Pruner {
 public:
  virtual ~Pruner() = default;
  // `trial` has just reported; `study.trials` holds every trial (this one included).
  virtual bool prune(const StudyView& study, const FrozenTrial& trial,
                     const SetSystemAttr& set_system_attr) = 0;
};

// `default_warmup`: n_warmup_steps when the config leaves it null.
std::unique_ptr<Pruner> make_pruner(const PrunerConfig& config, int64_t default_warmup);

}  // namespace rlrun::tune
