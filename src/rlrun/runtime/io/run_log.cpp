#include "rlrun/runtime/io/run_log.hpp"

#include <iostream>

namespace rlrun {

RunLog::RunLog(const std::string& path, bool echo)
    : file_(CheckedFile::run_file(path, CheckedFile::Mode::kAppend)), echo_(echo) {}

void RunLog::line(const std::string& text) {
  if (echo_) std::cout << text << std::endl;
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
