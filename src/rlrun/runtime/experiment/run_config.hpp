#pragma once
// The `run:` section of an experiment file, as plain data.
#include <cstdint>
#include <optional>
#include <string>

#include "rlrun/core/config_checks.hpp"
#include "rlrun/core/trusted_values.hpp"

namespace rlrun {

struct RunConfig {
  std::string name;                  // default: the config file's stem
  uint64_t seed = 0;                 // env i is seeded seed + i; all RNGs derive from it
  int64_t total_timesteps = 100000;  // env steps over all envs, as SB3's learn(total_timesteps)
  std::string out_dir = "runs";      // run directory = <out_dir>/<name>/seed<seed>
  std::optional<int> log_interval;   // progress.csv rows every N iterations (on-policy) or
                                     // episodes (off-policy); null = SB3's default (1 / 4)
  double console_interval = 2.0;     // min seconds between console tables
  int verbose = 1;                   // SB3's verbose: 0 = nothing on the console
  std::string init_from;             // model file whose weights start the run (empty: none)
  OutputPath tensorboard_log;        // SB3's tensorboard_log: DIR for TensorBoard event files
  std::optional<std::string> tb_log_name;  // SB3's tb_log_name; null = the run name
  bool tensorboard_images = false;         // the learning curve as a TensorBoard image at the end

  template <class V>
  void visit(V& v) {
    v("name", name, "run name (default: the config file name without .yaml)", RelativeName{});
    v("seed", seed, "random seed; env i gets seed + i");
    v("total_timesteps", total_timesteps, "total env steps to train for (all envs together)",
      in_range(1, 1e15));
    v("out_dir", out_dir, "root directory of run outputs", DirectoryPath{});
    v("log_interval", log_interval,
      "progress.csv row every N iterations (on-policy) / episodes (off-policy); null = SB3 default",
      at_least(1));
    v("console_interval", console_interval, "minimum seconds between console summaries",
      in_range(0, 1e9));
    v("verbose", verbose,
      "console output as SB3's verbose: 0 = none (log.txt and progress.csv are written all "
      "the same), 1 = the run's lines, tables and progress bar",
      in_range(0, 2));
    v("init_from", init_from,
      "model file whose weights (and normalisation statistics) start this run; empty = none");
    v("tensorboard_log", tensorboard_log,
      "directory for TensorBoard event files (SB3's tensorboard_log): each run writes "
      "DIR/<tb_log_name>_<N>/; empty = none");
    v("tb_log_name", tb_log_name,
      "name of this run's TensorBoard runs under tensorboard_log (null = the run name)",
      RelativeName{});
    v("tensorboard_images", tensorboard_images,
      "with tensorboard_log: add the learning curve as an image when the run finishes (off by "
      "default: drawing it costs about 60 ms, 7 % of a 1-second CartPole run)");
  }
};

}  // namespace rlrun
