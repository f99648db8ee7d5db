#pragma once
// Sweeps: one base experiment, a grid (or list) of overrides and a list of seeds, expanded into
// a manifest of fully resolved runs with stable ids (docs/sweeps.md). The sweep file:
//
//   base: ../cartpole_ppo.yaml           # relative to the sweep file
//   out_dir: runs/sweeps/cartpole_lr     # manifest.yaml, configs/ and runs/ go here
//   seeds: [1, 2, 3]
//   grid: {algo.learning_rate: [3.0e-4, 1.0e-3]}   # cartesian product of the values, or
//   list: [{algo.learning_rate: 3.0e-4}, {algo.learning_rate: 1.0e-3, algo.n_epochs: 4}]
//   set: {run.total_timesteps: 20000}     # for every run
//   slurm: {partition: debug, time: "00:30:00", cpus_per_task: 1, mem: 1G, extra: []}
//
// Every run writes TensorBoard event files to <out_dir>/tensorboard/<label>_seed<N>_1/ (or
// under the experiment's own run.tensorboard_log), so `tensorboard --logdir` compares them.
// A run's label names its overrides ("learning_rate=0.001"; "base" without any), its id adds
// the seed ("learning_rate=0.001/seed2"), its directory is <out_dir>/runs/<label>/seed<N>:
// the same sweep file always gives the same ids and directories.
#include <cstdint>
#include <string>
#include <vector>

#include "rlrun/core/config_node.hpp"
#include "rlrun/runtime/components/registry.hpp"
#include "rlrun/runtime/workflows/slurm_options.hpp"

namespace rlrun {

// The most runs one sweep expands into (each is a config file and a run directory).
inline constexpr int kMaxSweepRuns = 100000;

// A sweep file's free-form sections (grid, list, set) are read as nodes.
inline void decode(const ConfigNode& n, ConfigNode& out) { out = n; }
inline YAML::Node encode(const ConfigNode& n) { return n.yaml(); }

struct SweepRun {
  int index = 0;
  std::string id;     // <label>/seed<N>
  std::string label;  // the overrides, readable
  uint64_t seed = 0;
  std::string config;  // the run's resolved experiment file
  std::string run_dir;
};

struct Sweep {
  std::string name;
  std::string source;    // the sweep file
  std::string manifest;  // <out_dir>/manifest.yaml
  SlurmOptions slurm;
  std::vector<SweepRun> runs;
};

// What the command line adds to a sweep file (`rlrun sweep SWEEP.yaml --out DIR --set k=v`).
struct SweepOptions {
  std::string out_dir;           // instead of the file's out_dir
  std::vector<std::string> set;  // "key=value" for every run, after the file's `set:`
};

// Reads a sweep file, checks every override against the base experiment, writes
// <out_dir>/configs/<label>_seed<N>.yaml (each a complete experiment file, run.out_dir and
// run.name set so the run trains into its directory) and <out_dir>/manifest.yaml. Throws
// ConfigError naming the sweep file's line and column for a bad key or value, or the --set
// value that does not fit; a --set of a key the grid or list varies is a UsageError.
Sweep expand_sweep(const std::string& sweep_file, Registry& registry,
                   const SweepOptions& options = {});

// Where a sweep's runs write TensorBoard event files unless its experiment names a directory.
std::string sweep_tensorboard_dir(const std::string& sweep_out_dir);
// The `--set` values `sweep run` adds for `run` so that its untrusted config may write where
// the sweep itself writes (its own TensorBoard directory inside the sweep's directory).
std::vector<std::string> sweep_vouched_overrides(const Sweep& sweep, const SweepRun& run);

// Reads a manifest written by expand_sweep (paths in it are relative to its directory).
Sweep read_manifest(const std::string& manifest);

// What `sweep run` does with a run: skip a finished one, resume one with a checkpoint, start
// again one that began without leaving a checkpoint, start a new one.
enum class RunState { kNew, kFinished, kResumable, kPartial };
RunState run_state(const SweepRun& run);
// False when the run's directory holds a config.yaml other than the manifest's config for it:
// the sweep file was changed and expanded again after the run started. `sweep run` refuses to
// skip or resume such a run (it would keep the old settings silently).
bool run_config_matches(const SweepRun& run);
const char* to_string(RunState state);

// Where `sweep run` (without --index) keeps a run's console output:
// <out_dir>/logs/<label>/seed<N>.txt (the run directory's path below runs/; logs/run<index>.txt
// for a manifest that puts it elsewhere).
std::string run_console_log(const Sweep& sweep, const SweepRun& run);

// The sbatch script of a manifest: runtime/workflows/sbatch_script.hpp.

}  // namespace rlrun
