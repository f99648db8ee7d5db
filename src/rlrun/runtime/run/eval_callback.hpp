#pragma once
// `eval:` — SB3's EvalCallback with its two stop callbacks
// (stable_baselines3/common/callbacks.py), counting TOTAL env steps:
//   * every `freq` total steps (all n_envs counted; SB3's eval_freq counts per-env steps),
//     runs `n_episodes` on a separate env (seeded run.seed + n_envs + k for the k-th
//     evaluation) whose normalisation statistics are copied from training env 0 and frozen
//     (SB3 sync_envs_normalization);
//   * appends `timesteps,mean_reward,std_reward,mean_ep_length,success_rate,<metrics>` to
//     evaluations.csv (success_rate empty unless the env reports `is_success`; <metrics> the
//     env's info keywords, runtime/experiment/env_factory.hpp, each the mean over the episodes), records
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
#include "rlrun/runtime/experiment/eval_config.hpp"
#include "rlrun/runtime/run/callback.hpp"

namespace rlrun {

class EvalCallback : public Callback {
 public:
  EvalCallback(TrainingContext& context, const EvalConfig& config);
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
