#pragma once
// A scripted driver for CarRacing-v3 that reads the car and the track (not the pixels): it
// steers towards a point a few tiles ahead on the centre line (pure pursuit, R. C. Coulter,
// "Implementation of the Pure Pursuit Path Tracking Algorithm", CMU-RI-TR-92-01, 1992) and
// holds a speed that drops before sharp bends. Gymnasium has no such baseline; rlrun uses it
// to show the car and the rewards behave (a clean lap scores above Gymnasium's reward
// threshold of 900) and as `--policy line-follower` for eval and record.
#include <Eigen/Core>
#include <array>
#include <functional>

#include "rlrun/env.hpp"
#include "rlrun/env/race_track_state.hpp"

namespace rlrun {

// Continuous controls (steer, gas, brake) in CarRacing's action space for the car on track.
std::array<float, 3> line_follower_controls(const CarState& car, std::span<const TrackPoint> track);

// As a policy of the one env `env` (Discrete(5) actions when it is discrete). Throws
// UsageError unless the innermost env is CarRacing.
std::function<void(const Eigen::MatrixXf& obs, Eigen::MatrixXf& action)> line_follower_actions(
    Env& env);

}  // namespace rlrun
