#pragma once
// The `eval:` section of an experiment file, as plain data (run/eval_callback.hpp does the
// evaluating and says what each field means for a run).
#include <cstdint>
#include <optional>
#include <string>

#include "rlrun/core/config_checks.hpp"

namespace rlrun {

// The `section:` of the experiment file: SB3 EvalCallback + its two stop callbacks.
struct EvalConfig {
  int64_t freq = 0;     // total env steps between evaluations (0 = off)
  int n_episodes = 10;  // episodes per evaluation
  bool deterministic = true;
  std::optional<double> reward_threshold;  // stop once best mean reward >= this
  std::optional<int>
      max_no_improvement_evals;  // stop after more evals than this without a new best
  int min_evals = 0;             // evaluations before counting no-improvement
  std::string best_metric =
      "mean_reward";  // the evaluations.csv column best_model.zip is chosen by
  std::string best_direction = "maximize";
  // "file:line:col" of eval.best_metric, set by the experiment reader: the metric is checked
  // against the env's columns only once the evaluation env exists (not a visited field).
  std::string best_metric_where;
  template <class V>
  void visit(V& v) {
    v("freq", freq, "evaluate every `freq` TOTAL env steps (all envs counted; 0 = never)",
      non_negative());
    v("n_episodes", n_episodes, "episodes per evaluation", in_range(1, 1000000));
    v("deterministic", deterministic, "use the deterministic policy");
    v("reward_threshold", reward_threshold,
      "stop training once the best mean eval reward >= this (SB3 StopTrainingOnRewardThreshold; "
      "null = never)");
    v("max_no_improvement_evals", max_no_improvement_evals,
      "stop when more than this many evaluations in a row bring no new best (SB3 "
      "StopTrainingOnNoModelImprovement; null = never)",
      non_negative());
    v("min_evals", min_evals, "evaluations before no-improvement is counted", non_negative());
    v("best_metric", best_metric,
      "the evaluations.csv column that chooses best_model.zip: mean_reward (SB3's), success_rate "
      "or one of the env's metrics (mean_delay, ...)");
    v("best_direction", best_direction, "maximize or minimize best_metric",
      OneOf{{"maximize", "minimize"}});
  }
};

}  // namespace rlrun
