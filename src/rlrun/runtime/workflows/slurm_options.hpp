#pragma once
// The `slurm:` options of a sweep (sweep.hpp) and the check of their values against what
// sbatch reads from a `#SBATCH` line (sbatch_script.hpp says why they cannot be quoted).
#include <string>
#include <vector>

#include "rlrun/core/config_node.hpp"

namespace rlrun {

// A control character (< 0x20 or DEL): none may appear in a script's values.
bool is_control_char(char c);
// The value as it may be shown in a one-line message: quoted, control characters as \n, \r,
// \xNN.
std::string printable_value(const std::string& value);

struct SlurmOptions {
  std::string partition;
  std::string time = "01:00:00";
  int cpus_per_task = 1;
  std::string mem;
  std::vector<std::string> extra;  // more `#SBATCH` lines, e.g. "--qos=short"

  template <class V>
  void visit(V& v) {
    v("partition", partition, "sbatch --partition (empty: the cluster's default)");
    v("time", time, "sbatch --time per run");
    v("cpus_per_task", cpus_per_task, "sbatch --cpus-per-task; also each task's rlrun --threads");
    v("mem", mem, "sbatch --mem (empty: the cluster's default)");
    v("extra", extra, "further sbatch options, one per #SBATCH line (--option=value)");
  }
};

// "" when the value of slurm option `key` (time, mem, partition, extra, cpus_per_task) is one
// sbatch reads as meant from a `#SBATCH` line, else the problem and an example.
std::string slurm_value_problem(const std::string& key, const std::string& value);

// Checks every option of `options`, read from `slurm` (the sweep file's or the manifest's
// `slurm:` map): a bad value is a ConfigError at its file:line:col.
void check_slurm_options(const ConfigNode& slurm, const SlurmOptions& options);

}  // namespace rlrun
