#pragma once
// A run's messages: each line on stdout and appended to `<run_dir>/log.txt`. A failed write
// (a full disk) is an error at once, naming the file and the reason, not a log that silently
// stops.
#include <fstream>
#include <string>

namespace rlrun {

class RunLog {
 public:
  // Throws RuntimeFailure when the file cannot be opened.
  explicit RunLog(std::string path);
  // Prints and appends one line; throws RuntimeFailure when the file cannot be written.
  void line(const std::string& text);
  // The file itself (the console table of each progress row goes there too).
  std::ofstream& file() { return file_; }
  // Flushes and throws RuntimeFailure if any write to the file has failed.
  void check();

 private:
  std::string path_;
  std::ofstream file_;
};

}  // namespace rlrun
