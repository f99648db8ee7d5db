#pragma once
// Where `rlrun train --resume RUN_DIR|CHECKPOINT` (and `sweep run`) continues a run from. A
// checkpoint is data from anyone (docs/security.md): the one chosen must be a whole zip that
// rlrun can read, written by the run's algorithm, at a step inside the run. When the newest
// checkpoint is damaged (a disk that filled up, a copy cut short), the previous one is used and
// the skipped one named, instead of failing the resume.
#include <string>
#include <vector>

#include "rlrun/runtime/experiment/experiment.hpp"
#include "rlrun/runtime/io/model_file.hpp"

namespace rlrun {

class DirHandle;  // core/dir_handle.hpp

// `<run_dir>/checkpoints/step_<N>.zip` -> `<run_dir>`.
std::string run_dir_of_checkpoint(const std::string& checkpoint);

// The checkpoints to try, newest first: a run directory's checkpoints/step_<N>.zip files, or
// the one file given. Throws UsageError when there is nothing to resume from, saying why.
std::vector<std::string> resume_candidates(const std::string& run_dir_or_checkpoint);

struct ResumePoint {
  std::string path;
  ModelFile checkpoint;
  std::vector<std::string> skipped;  // "<path>: <reason>" of newer, unusable checkpoints
};

// Opens the first candidate that is readable and fits `experiment`. Throws RuntimeFailure
// (UsageError for a model file that is not a checkpoint) naming each one tried.
// Tensors are read within checkpoint_tensor_budget (runtime/io/model_budget.hpp).
ResumePoint open_resume_point(const std::vector<std::string>& candidates,
                              const Experiment& experiment, const Registry& registry);

// Removes what a killed process leaves behind in a run directory it owns: the temporary files
// of atomic writes (`*.tmp`, `*.tmp.XXXXXX`) in the run directory and in checkpoints/ (regular
// files only; a checkpoints/ that is a link is refused, never cleaned). Call with the run
// locked (runtime/io/run_lock.hpp).
void remove_stale_temporaries(const DirHandle& run_dir);

}  // namespace rlrun
