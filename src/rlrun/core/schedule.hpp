#pragma once
// Hyperparameter schedules as SB3 and rl-zoo write them: a constant (`3e-4`) or
// `lin_<initial>`, rl-zoo's linear_schedule (rl_zoo3/utils.py): value = progress_remaining *
// initial, where progress_remaining goes from 1 (start) to 0 (end of training).
#include <string>

namespace rlrun {

class Schedule {
 public:
  Schedule() = default;
  static Schedule constant(double value) { return Schedule(value, false); }
  static Schedule linear(double initial) { return Schedule(initial, true); }
  // "3e-4", "lin_0.001", "lin_2.5e-4"; throws std::invalid_argument on anything else.
  static Schedule parse(const std::string& text);

  // SB3's schedule call: progress_remaining = 1 - num_timesteps / total_timesteps.
  double operator()(double progress_remaining) const {
    return linear_ ? initial_ * progress_remaining : initial_;
  }
  double initial() const { return initial_; }
  bool is_linear() const { return linear_; }
  // Round-trips through parse(): "lin_0.001" or "0.0003".
  std::string str() const;

 private:
  Schedule(double initial, bool linear) : initial_(initial), linear_(linear) {}
  double initial_ = 0.0;
  bool linear_ = false;
};

}  // namespace rlrun
