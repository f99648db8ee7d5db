#pragma once
// The time/ keys of SB3's _dump_logs (stable_baselines3/common/on_policy_algorithm.py,
// off_policy_algorithm.py): time_elapsed (whole seconds) and fps, both over this session of
// learn(), on a monotonic clock started with it. SB3 divides the session's steps by
// max(elapsed, epsilon), so a row written a fraction of a millisecond in claims an absurd rate:
// rlrun's C++ envs collect CartPole's first 256-step rollout in about 0.4 ms, before any
// training, and SB3's formula printed "fps 667638" at time_elapsed 0 (issue 41). Over an
// interval that short the number says more about the timer than the rate, so such a row has
// no time/fps (progress.csv leaves the cell empty); the session summary line has the rate.
#include <cmath>
#include <cstdint>

#include "rlrun/core/logger.hpp"

namespace rlrun {

// The shortest interval an fps is computed over: timer resolution and scheduling are well
// below 1 % of it.
inline constexpr double kMinFpsSeconds = 0.1;

// Records time/fps (only once elapsed_seconds >= kMinFpsSeconds) and time/time_elapsed.
inline void record_session_time(Logger& log, double elapsed_seconds, int64_t session_timesteps) {
  if (elapsed_seconds >= kMinFpsSeconds)
    log.record("time/fps", std::floor(static_cast<double>(session_timesteps) / elapsed_seconds));
  log.record("time/time_elapsed", std::floor(elapsed_seconds));
}

}  // namespace rlrun
