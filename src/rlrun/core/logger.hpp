#pragma once
// Key/value logger with SB3's semantics (stable_baselines3/common/logger.py): algorithms
// `record("train/value_loss", v)` during an interval, then `dump(num_timesteps)` writes one
// row to every sink (progress.csv, the console table, log.txt) and starts a new interval.
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

namespace rlrun {

// Sorted by key, as SB3 prints them; std::less<> looks keys up without making a std::string.
using LogRow = std::map<std::string, double, std::less<>>;

class LogSink {
 public:
  virtual ~LogSink() = default;
  virtual void write(const LogRow& row, int64_t step) = 0;
  virtual void flush() {}
};

class Logger {
 public:
  // A key already recorded in this interval (every gradient step records the same few) costs
  // a lookup, no allocation.
  void record(std::string_view key, double value) {
    if (const auto it = row_.find(key); it != row_.end()) {
      it->second = value;
    } else {
      row_.emplace(std::string(key), value);
    }
  }
  void dump(int64_t step) {
    if (row_.empty()) return;
    for (auto& sink : sinks_) sink->write(row_, step);
    row_.clear();
  }
  void add_sink(std::unique_ptr<LogSink> sink) { sinks_.push_back(std::move(sink)); }
  void flush() {
    for (auto& sink : sinks_) sink->flush();
  }
  // The values recorded since the last dump (checkpoints keep them: the next row of a resumed
  // run is the row the uninterrupted run would have written).
  const LogRow& pending() const { return row_; }
  void restore_pending(LogRow row) { row_ = std::move(row); }

 private:
  LogRow row_;
  std::vector<std::unique_ptr<LogSink>> sinks_;
};

}  // namespace rlrun
