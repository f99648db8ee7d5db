#pragma once
// Gymnasium's hand-written lander controller, heuristic(env, s) in
// gymnasium/envs/box2d/lunar_lander.py (Gymnasium 1.0.0): steer the angle
// towards the pad and hold a hover height proportional to the horizontal
// offset; after a leg touches, only brake the fall. It reads only the
// observation. Gymnasium uses it as its physics demonstration (a landing scores
// above 200), and rlrun's tests use it the same way (`--policy heuristic`).
#include <Eigen/Core>
#include <array>
#include <functional>
#include <span>

#include "rlrun/env.hpp"

namespace rlrun {

// The action for observation `s`: Discrete (action[0] in {0, 1, 2, 3}) or, with
// `continuous`, the two throttles clipped to [-1, 1].
std::array<float, 2> lunar_lander_heuristic(std::span<const float> s, bool continuous);

// As a policy on `env` (one observation per column). Throws UsageError unless
// the innermost env is a LunarLander; discrete or continuous follows that env's
// config.
std::function<void(const Eigen::MatrixXf& obs, Eigen::MatrixXf& action)>
lunar_lander_heuristic_actions(Env& env);

}  // namespace rlrun
