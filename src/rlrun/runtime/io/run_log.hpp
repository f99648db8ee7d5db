#pragma once
// A run's messages: each line on stdout and appended to `<run_dir>/log.txt`, with the console
// table of every progress row (ConsoleTableSink writes into table()). Every write to the file
// is checked (core/checked_file.hpp): a full disk is an error at once, naming the file and the
// reason, not a log that silently stops.
#include <sstream>
#include <string>

#include "rlrun/core/checked_file.hpp"

namespace rlrun {

class RunLog {
 public:
  // Throws RuntimeFailure when the file cannot be opened.
  // `echo`: also print each line on stdout.
  explicit RunLog(const std::string& path, bool echo = true);
  // Prints and appends one line; throws RuntimeFailure when the file cannot be written.
  void line(const std::string& text);
  // Where the console tables for log.txt go; check() writes them out.
  std::ostream& table() { return tables_; }
  // Writes everything pending; throws RuntimeFailure if the file cannot be written.
  void check();

 private:
  CheckedFile file_;
  std::ostringstream tables_;
  bool echo_ = true;
};

}  // namespace rlrun
