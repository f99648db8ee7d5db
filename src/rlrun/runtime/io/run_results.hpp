#pragma once
// What finished (or running) run directories hold, read back for `rlrun report` and `rlrun
// plot`: each run's final return, success rate, wall time and learning curve, grouped by
// configuration across seeds.
//
// A run's configuration is its resolved config.yaml without what differs between seeds or only
// names where outputs go: run.seed, run.out_dir, run.tb_log_name (`rlrun sweep` gives each
// run <label>_seed<N>) and run.tensorboard_log. So a sweep's seeds of one grid point, or
// `rlrun train x.yaml --seed 1/2/3`, form one group; the group is labelled with run.name (a
// sweep run's label), made unique when two configurations share a name.
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace rlrun {

struct RunResult {
  std::string dir;
  std::string config_key;  // the resolved config minus the per-seed and output keys, as YAML
  std::string name;        // run.name
  uint64_t seed = 0;
  double final_return = 0;
  std::string return_source;  // "eval" (evaluations.csv's last row), "monitor" (last 100
                              // episodes) or "none" (no episode ended: final_return is NaN)
  std::optional<double> success_rate;
  double wall_seconds = 0;  // log.txt's training sessions added up (else progress.csv's)
  double timesteps = 0;     // the `finished` marker's count, else model.zip's (or progress.csv's
                            // last time/total_timesteps when that is further)
  // progress.csv as columns (every column, NaN where a row left it empty).
  std::map<std::string, std::vector<double>> progress;
};

struct RunGroup {
  std::string label;
  std::vector<RunResult> runs;  // by seed
};

// Run directories: each argument is a run directory (it holds config.yaml) or a directory
// searched recursively for them. Throws UsageError when an argument holds none.
std::vector<std::string> find_run_dirs(const std::vector<std::string>& paths);
// Throws RuntimeFailure for a directory without config.yaml.
RunResult read_run(const std::string& dir);
// read_run of every run directory find_run_dirs finds.
std::vector<RunResult> read_runs(const std::vector<std::string>& paths);
std::vector<RunGroup> group_runs(const std::vector<RunResult>& runs);

// Statistics over one group's seeds, as rliable reports them for a single task (Agarwal et
// al., "Deep RL at the Edge of the Statistical Precipice", NeurIPS 2021;
// google-research/rliable, library.get_interval_estimates): the interquartile mean (IQM: the
// mean of the middle 50 %, scipy.stats.trim_mean(x, 0.25)) with a percentile bootstrap 95 %
// confidence interval (2000 resamples of the runs with replacement, a fixed seed so reports
// are reproducible). std is numpy's default (ddof = 0).
struct SeedStatistics {
  int n = 0;
  double mean = 0, std = 0, median = 0, iqm = 0, iqm_low = 0, iqm_high = 0;
};
// NaN values (runs without returns) are left out; n counts the rest.
SeedStatistics seed_statistics(const std::vector<double>& values);
double interquartile_mean(std::vector<double> values);

}  // namespace rlrun
