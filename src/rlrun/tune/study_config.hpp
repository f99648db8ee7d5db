#pragma once
// The study file of `rlrun tune` (docs/tune.md): one base experiment, a search space, and how
// trials are run, judged, sampled and pruned — rl-zoo's `--optimize` options as a file.
//
//   name: cartpole_ppo                 # the Optuna study name (default: the file's stem)
//   base: ../cartpole_ppo.yaml         # every trial starts from it (relative to this file)
//   out_dir: runs/tune/cartpole_ppo    # study.journal and trials/ (default runs/tune/<name>)
//   n_trials: 100                      # in total, over every worker and every restart
//   seeds_per_trial: 2                 # run.seed, run.seed + 1, ...: the objective is their mean
//   n_timesteps: 50000                 # per seed (default: the base's run.total_timesteps)
//   n_evaluations: 10                  # per seed; intermediate values for the pruner
//   eval_episodes: 5                   # per evaluation (the zoo's --eval-episodes)
//   timeout: 3600                      # seconds per worker: no new trial after it
//   objective: {metric: mean_reward, direction: maximize, reduce: last}
//   sampler: {type: tpe, seed: 1, n_startup_trials: 10}
//   pruner: {type: median, n_startup_trials: 5}
//   space: zoo                         # or parameters: tune/search_space.hpp
//   set: {env.n_envs: 8}               # fixed overrides for every trial
//   slurm: {partition: debug, time: "02:00:00"}
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "rlrun/core/config_node.hpp"
#include "rlrun/runtime/workflows/sweep.hpp"
#include "rlrun/tune/pruner.hpp"
#include "rlrun/tune/search_space.hpp"

namespace rlrun {
class Registry;
}

namespace rlrun::tune {

struct ObjectiveConfig {
  std::string metric = "mean_reward";  // a column of evaluations.csv or progress.csv
  std::string direction = "maximize";
  std::string reduce = "last";  // per seed: last, best or mean of the column's rows
  template <class V>
  void visit(V& v) {
    v("metric", metric,
      "the column to optimise: one of evaluations.csv (mean_reward, success_rate, ...) or "
      "progress.csv (rollout/ep_rew_mean, ...)");
    v("direction", direction, "maximize or minimize", OneOf{{"maximize", "minimize"}});
    v("reduce", reduce,
      "per seed: the last row's value (the zoo's), the best row's or the mean of all rows",
      OneOf{{"last", "best", "mean"}});
  }
};

struct SamplerConfig {
  std::string type = "tpe";
  std::optional<uint64_t> seed;  // null: the base experiment's run.seed
  // TPE (Optuna's TPESampler as rl-zoo creates it: multivariate, 10 random trials first).
  int n_startup_trials = 10;
  int n_ei_candidates = 24;
  bool multivariate = true;
  template <class V>
  void visit(V& v) {
    v("type", type, "tpe or random", OneOf{{"tpe", "random"}});
    v("seed", seed, "sampler seed (null: the base experiment's run.seed)");
    v("n_startup_trials", n_startup_trials, "tpe: random trials before TPE starts", non_negative());
    v("n_ei_candidates", n_ei_candidates, "tpe: candidates drawn per sample", at_least(1));
    v("multivariate", multivariate, "tpe: sample the shared parameters jointly (rl-zoo: true)");
  }
};

struct StudyConfig {
  std::string source;  // the study file, absolute
  std::string name;
  std::string base;     // the base experiment file, absolute
  std::string out_dir;  // absolute
  std::string storage;  // the journal file, absolute
  int n_trials = 100;
  int seeds_per_trial = 1;
  int64_t n_timesteps = 0;  // resolved
  int n_evaluations = 1;    // resolved
  int eval_episodes = 5;
  std::optional<double> timeout;
  ObjectiveConfig objective;
  SamplerConfig sampler;
  PrunerConfig pruner;
  std::shared_ptr<const StudySpace> space;
  std::vector<Override> set;  // the file's `set:` then the command line's --set
  SlurmOptions slurm;
  uint64_t base_seed = 0;  // the base experiment's run.seed
  std::string algo_id;

  bool maximize() const { return objective.direction == "maximize"; }
  // The overrides of one seed of a trial: its parameters, then where it writes.
  std::vector<std::string> seed_overrides(const std::vector<Override>& params, int trial_number,
                                          int seed_index) const;
  std::string trial_dir(int trial_number) const;  // <out_dir>/trials/trial_<N>
};

// Reads and checks a study file (trusted: the user's own), its base experiment and every
// fixed override; `set` adds command-line overrides after the file's. ConfigError at the line.
// `out_dir`: instead of the file's (the command line's --out); `n_timesteps`: instead of the
// file's (--n-timesteps). A fixed override of a key the study sets for every trial (run.out_dir,
// run.name, eval.freq, eval.n_episodes, checkpoint.freq; run.total_timesteps when the study
// names n_timesteps) is refused with the study's own option, rather than silently replaced.
StudyConfig load_study(const std::string& path, Registry& registry,
                       const std::vector<std::string>& set = {}, const std::string& out_dir = "",
                       std::optional<int64_t> n_timesteps = std::nullopt);

}  // namespace rlrun::tune
