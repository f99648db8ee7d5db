#include "rlrun/runtime/io/run_log_marks.hpp"

#include <algorithm>
#include <limits>
#include <map>
#include <optional>
#include <sstream>

#include "rlrun/core/dir_handle.hpp"
#include "rlrun/core/errors.hpp"
#include "rlrun/core/plural.hpp"
#include "rlrun/runtime/io/log_sinks.hpp"
#include "rlrun/runtime/io/run_file_bounds.hpp"

namespace rlrun {

namespace {

// The first `max_lines` lines of one of the run's CSV files (all by default), within the
// bounds of runtime/io/run_file_bounds.hpp; none when it does not exist.
std::vector<std::string> read_lines(const DirHandle& run, const std::string& name,
                                    size_t max_lines = std::numeric_limits<size_t>::max()) {
  std::vector<std::string> lines;
  std::optional<LineReader> in = run.read_lines(name, kMaxRunCsvBytes, kMaxRunCsvLineBytes);
  for (std::string line; in && lines.size() < max_lines && in->next(line);) lines.push_back(line);
  return lines;
}

// Rows written under header `from` re-expressed under header `to` (every key of `to` was in
// `from`: headers only grow). Keys missing from `from` stay empty.
std::string project_row(const std::string& row, const std::vector<std::string>& from,
                        const std::vector<std::string>& to) {
  const std::vector<std::string> cells = split_csv_line(row);
  std::map<std::string, std::string> by_key;
  for (size_t i = 0; i < from.size() && i < cells.size(); ++i) by_key[from[i]] = cells[i];
  std::string out;
  for (size_t i = 0; i < to.size(); ++i) {
    if (i) out += ',';
    const auto it = by_key.find(to[i]);
    if (it != by_key.end()) out += it->second;
  }
  return out;
}

}  // namespace

void write_log_marks(StateWriter out, const DirHandle& run_dir,
                     const std::vector<std::string>& files) {
  out.put_int("count", static_cast<int64_t>(files.size()));
  for (size_t i = 0; i < files.size(); ++i) {
    StateWriter file = out.sub(std::to_string(i));
    const std::vector<std::string> lines = read_lines(run_dir, files[i]);
    file.put_string("name", files[i]);
    file.put_int("lines", static_cast<int64_t>(lines.size()));
    file.put_string("first_line", lines.empty() ? std::string() : lines.front());
  }
}

void restore_log_marks(const StateReader& in, const DirHandle& run_dir,
                       const std::vector<std::string>& expected) {
  const int64_t count = in.get_int("count");
  if (count < 0 || count > static_cast<int64_t>(expected.size()))
    throw RuntimeFailure("cannot resume: the checkpoint marks " + std::to_string(count) +
                         " log files, this run writes " + std::to_string(expected.size()));
  for (int64_t i = 0; i < count; ++i) {
    const StateReader file = in.sub(std::to_string(i));
    const std::string name = file.get_string("name");
    if (std::find(expected.begin(), expected.end(), name) == expected.end())
      throw RuntimeFailure("cannot resume: the checkpoint names a log file '" + name +
                           "' that this run does not write (a checkpoint from elsewhere?)");
    const int64_t lines_recorded = file.get_int("lines");
    if (lines_recorded < 0)
      throw RuntimeFailure("cannot resume: the checkpoint records " +
                           count_of(lines_recorded, "line") + " of " + name);
    const auto kept = static_cast<size_t>(lines_recorded);
    const std::string path = run_dir.child(name);
    if (kept == 0) {
      run_dir.remove(name);
      continue;
    }
    std::vector<std::string> lines = read_lines(run_dir, name, kept);
    if (lines.size() < kept)
      throw RuntimeFailure("cannot resume: " + path + " has " + std::to_string(lines.size()) +
                           " lines, the checkpoint recorded " + std::to_string(kept) +
                           " (was it edited or truncated since?)");
    lines.resize(kept);
    const std::string first_line = file.get_string("first_line");
    if (lines.front() != first_line) {
      // The header grew after the checkpoint: put the kept rows back under the old header.
      const std::vector<std::string> from = split_csv_line(lines.front());
      const std::vector<std::string> to = split_csv_line(first_line);
      lines.front() = first_line;
      for (size_t r = 1; r < lines.size(); ++r) lines[r] = project_row(lines[r], from, to);
    }
    std::ostringstream text;
    for (const std::string& line : lines) text << line << '\n';
    run_dir.write_atomic(name, text.str());
  }
}

}  // namespace rlrun
