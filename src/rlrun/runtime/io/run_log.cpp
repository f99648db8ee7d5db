#include "rlrun/runtime/io/run_log.hpp"

#include <iostream>

namespace rlrun {

RunLog::RunLog(const std::string& path)
    : file_(CheckedFile::run_file(path, CheckedFile::Mode::kAppend)) {}

void RunLog::line(const std::string& text) {
  std::cout << text << std::endl;
  check();  // tables written before this line stay before it
  file_ << text << '\n';
  file_.flush();
}

void RunLog::check() {
  const std::string pending = tables_.str();
  if (!pending.empty()) {
    file_ << pending;
    tables_.str("");
  }
  file_.flush();
}

}  // namespace rlrun
