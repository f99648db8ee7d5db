#include "rlrun/runtime/run_log.hpp"

#include <cerrno>
#include <cstring>
#include <iostream>

#include "rlrun/core/errors.hpp"

namespace rlrun {

RunLog::RunLog(std::string path) : path_(std::move(path)), file_(path_, std::ios::app) {
  if (!file_) throw RuntimeFailure("cannot write " + path_ + ": " + std::strerror(errno));
}

void RunLog::line(const std::string& text) {
  std::cout << text << std::endl;
  file_ << text << std::endl;
  check();
}

void RunLog::check() {
  file_.flush();
  if (!file_)
    throw RuntimeFailure("cannot write " + path_ + ": " +
                         (errno ? std::strerror(errno) : "write failed") +
                         " (is the disk full?)");
}

}  // namespace rlrun
