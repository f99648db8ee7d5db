#pragma once
// Sinks for Logger: progress.csv (SB3's CSVOutputFormat) and the console table (SB3's
// HumanOutputFormat), plus a line sink for log.txt.
#include <chrono>
#include <cstdio>
#include <fstream>
#include <functional>
#include <ostream>
#include <string>
#include <vector>

#include "rlrun/core/checked_file.hpp"
#include "rlrun/core/logger.hpp"

namespace rlrun {

// progress.csv: one row per dump, header of every key seen so far. When a new key appears
// (e.g. rollout/ep_rew_mean after the first finished episode) the file is rewritten with the
// wider header and empty cells in older rows, exactly as SB3 does.
// The cells of one line of a CSV file without quoting (progress.csv: keys and numbers).
std::vector<std::string> split_csv_line(const std::string& line);

class CsvSink : public LogSink {
 public:
  // `append`: continue an existing file (resumed runs), keeping its header.
  CsvSink(std::string path, bool append = false);
  void write(const LogRow& row, int64_t step) override;
  void flush() override;

 private:
  void rewrite_with_header();
  std::string path_;
  std::vector<std::string> keys_;
  CheckedFile file_;  // every row flushed and checked (core/checked_file.hpp)
};

// SB3-style table on a stream (stdout, log.txt), at most one every `min_interval_s` seconds (plus the last one
// via flush), so that fast runs do not scroll thousands of tables.
class ConsoleTableSink : public LogSink {
 public:
  // `before_print` runs before each table (e.g. to erase a progress bar).
  ConsoleTableSink(std::ostream& out, double min_interval_s,
                   std::function<void()> before_print = {})
      : out_(out), min_interval_s_(min_interval_s), before_print_(std::move(before_print)) {}
  void write(const LogRow& row, int64_t step) override;
  void flush() override;

 private:
  void print(const LogRow& row) const;
  std::ostream& out_;
  double min_interval_s_;
  std::function<void()> before_print_;
  std::chrono::steady_clock::time_point last_print_{};
  bool printed_any_ = false;
  LogRow last_unprinted_;
};

// Formats a value as SB3 does in its table: integers plainly, others with 3 significant digits.
std::string format_log_value(double value);

}  // namespace rlrun
