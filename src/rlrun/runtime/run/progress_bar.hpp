#pragma once
// A one-line progress bar with ETA on a terminal (SB3's progress_bar=True), redrawn at most
// 10 times a second. Does nothing when stdout is not a terminal.
#include <chrono>
#include <cstdint>

namespace rlrun {

class ProgressBar {
 public:
  ProgressBar(int64_t total, bool enabled);
  void update(int64_t done);
  // Erases the bar so that other output starts on a clean line.
  void clear();
  void finish();

 private:
  int64_t total_;
  bool enabled_;
  bool drawn_ = false;
  std::chrono::steady_clock::time_point start_, last_draw_;
};

}  // namespace rlrun
