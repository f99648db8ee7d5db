#pragma once
// The sbatch script of a sweep (`rlrun sweep slurm`), written so that no value in it can become
// a command (docs/security.md: generated scripts quote every value).
//
// Two languages read the script. bash runs its body: every value there (the rlrun binary, the
// manifest) is a POSIX single-quoted word. sbatch reads the `#SBATCH` lines before bash runs,
// with a tokenizer of its own (Slurm's src/sbatch/opt.c, _get_argument: whitespace splits,
// '...' and "..." group, backslash escapes one character, an unquoted '#' starts a comment) and
// a line ends at the newline whatever the quoting. So a `#SBATCH` value cannot be quoted the
// way bash words are: the sweep's own options (time, mem, partition, extra) are checked
// against what Slurm accepts for them instead, and only the --output path, which rlrun makes
// from out_dir, is quoted for sbatch's tokenizer. No control character (newline, carriage
// return, ...) may appear anywhere in the script's values.
#include <string>
#include <vector>

#include "rlrun/core/config_node.hpp"
#include "rlrun/runtime/workflows/slurm_options.hpp"
#include "rlrun/runtime/workflows/sweep.hpp"

namespace rlrun {

// `text` as one POSIX shell word: 'text', each ' written as '\''. Safe for any bytes but NUL.
std::string shell_quote(const std::string& text);

// "" when `path` may appear in the script, else why not (a control character).
std::string script_path_problem(const std::string& path);

// An sbatch array job: every task runs `command` ("$SLURM_ARRAY_TASK_ID" tells it which it
// is), output in output_dir/%A_%a.out.
struct SlurmArrayJob {
  std::string name;        // the job name (reduced to [A-Za-z0-9._+-])
  std::string script;      // where the script will be (named in its comment)
  std::string output_dir;  // the tasks' console output
  int tasks = 1;           // --array=0-(tasks-1)
  SlurmOptions options;
  std::vector<std::string> comment;  // lines after #!/bin/bash
  std::string command;               // the shell command line, every value shell_quote()d
};
std::string slurm_array_script(const SlurmArrayJob& job);

// The sbatch script for the manifest: an array job whose task i runs
// `<rlrun> --threads <1|2> sweep run <manifest> --index i <run_args...>`, logs in
// <out_dir>/slurm/. `run_args` are `sweep slurm`'s --set and --plugin as `sweep run` takes
// them, each a quoted word. Throws UsageError when a path, an argument or an option cannot be
// written safely.
std::string slurm_script(const Sweep& sweep, const std::string& rlrun_binary,
                         const std::vector<std::string>& run_args = {});

}  // namespace rlrun
