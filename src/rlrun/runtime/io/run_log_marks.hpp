#pragma once
// How far a run's append-only CSV files (progress.csv, the monitor files, evaluations.csv) had
// got when a checkpoint was written, and cutting them back to that point when the run
// resumes. A run killed some time after its last checkpoint has already written rows that the
// resumed run will write again; without the cut they would appear twice (the common complaint
// about resumed SB3 runs: duplicated monitor rows and restarted progress files).
//
// A mark is the file's line count and its first line. progress.csv's header can grow after
// the checkpoint (a key first recorded later rewrites the file with a wider header, as SB3's
// CSVOutputFormat does); then the kept rows are projected back onto the recorded header.
#include <string>
#include <vector>

#include "rlrun/core/state_dict.hpp"

namespace rlrun {

class DirHandle;  // core/dir_handle.hpp

// `files` are names in `run_dir`; a file that does not exist is recorded as empty. Files are
// read without following links, within runtime/io/run_file_bounds.hpp.
void write_log_marks(StateWriter out, const DirHandle& run_dir,
                     const std::vector<std::string>& files);

// Cuts every recorded file back to its mark (atomically). A checkpoint is untrusted data: only
// the names in `expected` (the files this run appends to, as write_log_marks was given them)
// are touched, so a crafted name such as "../../x" is refused, never joined to the run
// directory. Throws RuntimeFailure naming the file when one is unexpected, or shorter than its
// mark (edited or truncated since the checkpoint).
void restore_log_marks(const StateReader& in, const DirHandle& run_dir,
                       const std::vector<std::string>& expected);

}  // namespace rlrun
