#pragma once
// `eval:` — SB3's EvalCallback with its two stop callbacks
// (stable_baselines3/common/callbacks.py), counting TOTAL env steps:
//   * every `freq` total steps (all n_envs counted; SB3's eval_freq counts per-env steps),
//     runs `n_episodes` on a separate env (seeded run.seed + n_envs + k for the k-th
//     evaluation) whose normalisation statistics are copied from training env 0 and frozen
//     (SB3 sync_envs_normalization);
//   * appends `timesteps,mean_reward,std_reward,mean_ep_length,success_rate,<metrics>` to
//     evaluations.csv (success_rate empty unless the env reports `is_success`; <metrics> the
//     env's info keywords, runtime/env_factory.hpp, each the mean over the episodes), records
//     eval/mean_reward, eval/mean_ep_length (and eval/success_rate, eval/<metric>) for
//     progress.csv;
//   * saves best_model.zip on a new best mean reward, or on a new best of `best_metric`
//     (any evaluations.csv column, e.g. an env metric such as mean_delay) in `best_direction`:
//     SB3 always selects on the return; an env whose return is a poor proxy for what the user
//     measures (sumo-rl's diff-waiting-time reward telescopes to the waiting time at the
//     episode's last step) selects on the measure itself;
//   * reward_threshold: stops once the best mean reward >= it (StopTrainingOnRewardThreshold);
//   * max_no_improvement_evals / min_evals: stops when, after more than min_evals evaluations,
//     more than max_no_improvement_evals evaluations in a row brought no new best model
//     (StopTrainingOnNoModelImprovement, same counting as SB3).
#include <fstream>
#include <limits>
#include <string>

#include "rlrun/core/checked_file.hpp"
#include "rlrun/core/config_checks.hpp"
#include "rlrun/runtime/callback.hpp"

namespace rlrun {

// The `section:` of the experiment file: SB3 EvalCallback + its two stop callbacks.
struct EvalConfig {
  int64_t freq = 0;         // total env steps between evaluations (0 = off)
  int n_episodes = 10;      // episodes per evaluation
  bool deterministic = true;
  std::optional<double> reward_threshold;       // stop once best mean reward >= this
  std::optional<int> max_no_improvement_evals;  // stop after more evals than this without a new best
  int min_evals = 0;                            // evaluations before counting no-improvement
  std::string best_metric = "mean_reward";      // the evaluations.csv column best_model.zip is chosen by
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
      "stop training once the best mean eval reward >= this (SB3 StopTrainingOnRewardThreshold; null = never)");
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


class EvalCallback : public Callback {
 public:
  explicit EvalCallback(TrainingContext& context);
  bool on_step(int64_t num_timesteps) override;
  void write_state(StateWriter& out) const override;
  void read_state(const StateReader& in) override;
  void flush() override { csv_.flush(); }

  double best_mean_reward() const { return best_; }
  int evaluations() const { return evaluations_; }

 private:
  bool check_stop_rules();

  TrainingContext& context_;
  const EvalConfig& config_;
  EnvPtr env_;
  int64_t next_;
  int evaluations_ = 0;
  double best_ = -std::numeric_limits<double>::infinity();  // best mean reward (reward_threshold)
  // The best of best_metric, signed so that larger is better (-value when minimising): a new
  // one saves best_model.zip. Equal to best_ when best_metric is mean_reward.
  double best_score_ = -std::numeric_limits<double>::infinity();
  // StopTrainingOnNoModelImprovement state (on best_score_: "no new best model").
  double last_best_ = -std::numeric_limits<double>::infinity();
  int no_improvement_evals_ = 0;
  std::vector<std::string> metric_keys_;  // the env's metrics: evaluations.csv columns, eval/<key>
  CheckedFile csv_;  // evaluations.csv, every row flushed and checked (core/checked_file.hpp)
};

}  // namespace rlrun
