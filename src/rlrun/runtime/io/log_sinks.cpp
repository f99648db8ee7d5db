#include "rlrun/runtime/io/log_sinks.hpp"

#include <fcntl.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <optional>
#include <sstream>

#include "rlrun/core/errors.hpp"
#include "rlrun/core/line_reader.hpp"
#include "rlrun/core/regular_file.hpp"
#include "rlrun/runtime/io/run_directory.hpp"
#include "rlrun/runtime/io/run_file_bounds.hpp"

namespace rlrun {

namespace {

std::string csv_value(double v) {
  if (std::isnan(v)) return "nan";
  std::ostringstream out;
  out.precision(9);
  out << v;
  return out.str();
}

}  // namespace

std::vector<std::string> split_csv_line(const std::string& line) {
  std::vector<std::string> cells;
  std::stringstream ss(line);
  for (std::string cell; std::getline(ss, cell, ',');) cells.push_back(cell);
  if (!line.empty() && line.back() == ',') cells.emplace_back();
  return cells;
}

namespace {

// progress.csv's lines (a resumed run's: from anyone), within runtime/io/run_file_bounds.hpp;
// none when it does not exist.
std::optional<LineReader> read_progress(const std::string& path) {
  FileDescriptor fd = open_regular_file(AT_FDCWD, path, O_RDONLY, path);
  if (!fd) return std::nullopt;
  return LineReader(std::move(fd), path, kMaxRunCsvBytes, kMaxRunCsvLineBytes);
}

}  // namespace

CsvSink::CsvSink(std::string path, bool append) : path_(std::move(path)) {
  if (append) {
    std::optional<LineReader> in = read_progress(path_);
    std::string header;
    if (in && in->next(header)) keys_ = split_csv_line(header);
  }
  file_ = CheckedFile::run_file(path_,
                                append ? CheckedFile::Mode::kAppend : CheckedFile::Mode::kTruncate);
}

void CsvSink::rewrite_with_header() {
  file_.close();
  std::vector<std::string> lines;
  if (std::optional<LineReader> in = read_progress(path_)) {
    std::string line;
    in->next(line);  // old header
    while (in->next(line)) lines.push_back(line);
  }
  // Atomically: a full disk leaves the old file, not a truncated one.
  std::string text;
  for (size_t i = 0; i < keys_.size(); ++i) text += (i ? "," : "") + keys_[i];
  text += '\n';
  for (const auto& line : lines) {
    const size_t cells = split_csv_line(line).size();
    text += line + std::string(keys_.size() - std::min(cells, keys_.size()), ',') + '\n';
  }
  write_text_atomic(path_, text);
  file_ = CheckedFile::run_file(path_, CheckedFile::Mode::kAppend);
}

void CsvSink::write(const LogRow& row, int64_t /*step*/) {
  bool new_keys = false;
  for (const auto& [key, value] : row) {
    if (std::find(keys_.begin(), keys_.end(), key) == keys_.end()) {
      keys_.push_back(key);
      new_keys = true;
    }
  }
  if (new_keys) rewrite_with_header();
  for (size_t i = 0; i < keys_.size(); ++i) {
    if (i) file_ << ',';
    const auto it = row.find(keys_[i]);
    if (it != row.end()) file_ << csv_value(it->second);
  }
  file_ << '\n';
  file_.flush();  // throws RuntimeFailure naming the file and errno (ENOSPC) on a full disk
}

void CsvSink::flush() { file_.flush(); }

std::string format_log_value(double v) {
  if (std::isnan(v)) return "nan";
  if (std::floor(v) == v && std::abs(v) < 1e15) {
    std::ostringstream out;
    out << static_cast<long long>(v);
    return out.str();
  }
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.3g", v);
  return buffer;
}

void ConsoleTableSink::write(const LogRow& row, int64_t /*step*/) {
  const auto now = std::chrono::steady_clock::now();
  const double since = std::chrono::duration<double>(now - last_print_).count();
  if (printed_any_ && since < min_interval_s_) {
    last_unprinted_ = row;
    return;
  }
  print(row);
  last_print_ = now;
  printed_any_ = true;
  last_unprinted_.clear();
}

void ConsoleTableSink::flush() {
  if (!last_unprinted_.empty()) print(last_unprinted_);
  last_unprinted_.clear();
}

void ConsoleTableSink::print(const LogRow& row) const {
  // SB3 HumanOutputFormat: group "a/b" keys under "a/", indent the leaf names.
  std::vector<std::pair<std::string, std::string>> lines;
  std::string group;
  for (const auto& [key, value] : row) {
    const auto slash = key.find('/');
    const std::string prefix = slash == std::string::npos ? "" : key.substr(0, slash);
    if (prefix != group && !prefix.empty()) lines.emplace_back(prefix + "/", "");
    group = prefix;
    lines.emplace_back(slash == std::string::npos ? key : "    " + key.substr(slash + 1),
                       format_log_value(value));
  }
  size_t key_width = 0, value_width = 0;
  for (const auto& [k, v] : lines) {
    key_width = std::max(key_width, k.size());
    value_width = std::max(value_width, v.size());
  }
  const std::string dashes(key_width + value_width + 7, '-');
  std::ostringstream out;
  out << dashes << '\n';
  for (const auto& [k, v] : lines)
    out << "| " << k << std::string(key_width - k.size(), ' ') << " | " << v
        << std::string(value_width - v.size(), ' ') << " |\n";
  out << dashes << '\n';
  if (before_print_) before_print_();
  out_ << out.str() << std::flush;
}

}  // namespace rlrun
