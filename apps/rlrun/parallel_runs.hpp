#pragma once
// `rlrun train -j N a.yaml b.yaml ...` and `rlrun sweep run -j N`: up to N trainings at once,
// each a child process such as `rlrun --threads 1 train <config> <same options>` (one core
// each, so N = 2 fills this machine). Each child's console output goes to a temporary log file (kept when a run fails;
// log.txt in the run directory has it too); one line per finished run gives its summary, or
// the end of its output on failure.
//
// The children run in their own process group, so a Ctrl-C at the terminal reaches only this
// process, which forwards exactly one SIGINT to each child (each then checkpoints at its next
// safe point, see runtime/trainer.hpp); a second Ctrl-C is forwarded too and stops them at once.
#include <string>
#include <vector>

namespace rlrun::cli {

// One child process: `rlrun <args...>`, shown as `label` in the summary lines.
struct ChildRun {
  std::string label;
  std::vector<std::string> args;
};

// Runs up to `jobs` children at once. Returns 0 when every run succeeded, 130 when
// interrupted, 1 when any run failed.
int run_in_parallel(const std::vector<ChildRun>& runs, int jobs, const std::string& what);

// `rlrun train -j N`: each config as `rlrun --threads 1 train <config> <child_options>`.
int train_in_parallel(const std::vector<std::string>& configs,
                      const std::vector<std::string>& child_options, int jobs);

}  // namespace rlrun::cli
