#pragma once
// `rlrun train -j N a.yaml b.yaml ...` and `rlrun sweep run -j N`: up to N trainings at once,
// each a child process such as `rlrun --threads 1 train <config> <same options>` (one core
// each, so N = 2 fills this machine). One line per finished run gives its summary, or the end
// of its output on failure.
//
// Each child's console output goes to its ChildRun::log_path when it has one (`sweep run`:
// <out_dir>/logs/<run id>.txt, kept for the user and appended to when the run is resumed), else
// to a file in a private temporary directory that is removed at the end unless a run failed
// (`train -j`, whose runs' log.txt keep the same output).
//
// The children run in their own process group, so a Ctrl-C at the terminal reaches only this
// process, which forwards exactly one SIGINT to each child (each then checkpoints at its next
// safe point, see runtime/run/trainer.hpp); a second Ctrl-C is forwarded too and stops them at once.
#include <string>
#include <vector>
#include "rlrun/core/execution_context.hpp"

namespace rlrun::cli {

// One child process: `rlrun <args...>`, shown as `label` in the summary lines.
struct ChildRun {
  std::string label;
  std::vector<std::string> args;
  std::string log_path;  // its console output is appended here; "" = a temporary file
};

// Runs up to `jobs` children at once. `noun` names one child in messages ("run",
// "experiment"); `logs` says where the console output goes, for the first line ("" when the
// children have no log_path: the temporary directory is named). Returns 0 when every run
// succeeded, 130 when interrupted, 1 when any run failed.
int run_in_parallel(const std::vector<ChildRun>& runs, int jobs, const std::string& noun,
                    const std::string& logs = "");

// This rlrun binary's path (what child processes and sbatch scripts run).
std::string own_binary();

// `rlrun train -j N`: each config as `rlrun --threads T train <config> <child_options>`.
int train_in_parallel(const std::vector<std::string>& configs,
                      const std::vector<std::string>& child_options, int jobs, int threads_per_run);

// The threads each of `jobs` runs at once gets when they share this run's: an equal share,
// at least 1 (runs sharing cores slow each other's hand-offs; results never change).
int threads_per_job(const ExecutionContext& execution, int jobs);

}  // namespace rlrun::cli
