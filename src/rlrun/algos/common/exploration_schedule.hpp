#pragma once
// DQN's epsilon schedule: SB3 common/utils.py get_linear_fn(start, end, end_fraction), which
// DQN._setup_model builds from exploration_initial_eps, exploration_final_eps and
// exploration_fraction. The value falls linearly from `start` to `end` over the first
// `end_fraction` of training and stays at `end` afterwards.
namespace rlrun {

struct LinearDecay {
  double start = 1.0;
  double end = 0.05;
  double end_fraction = 0.1;  // > 0 (SB3 divides by it)

  // progress_remaining goes from 1 (start of training) to 0 (end).
  double operator()(double progress_remaining) const {
    const double progress = 1.0 - progress_remaining;
    // Strictly greater, as SB3: at progress == end_fraction the linear branch already gives end.
    if (progress > end_fraction) return end;
    return start + progress * (end - start) / end_fraction;
  }
};

}  // namespace rlrun
