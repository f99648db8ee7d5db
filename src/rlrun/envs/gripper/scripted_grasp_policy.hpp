#pragma once
// A hand-written controller for GripperLift-v0 / GripperLiftEasy-v0 (`--policy scripted` in
// eval and record): move above the cube with the fingers open, descend until the grasp point
// is at the cube's centre, close, and lift once both fingers hold it. It reads the simulated
// world, not the observation, and keeps no memory (each action follows from the state), so it
// shows that the task is solvable with the env's actions and forces.
#include <Eigen/Core>
#include <array>
#include <functional>

#include "rlrun/env.hpp"
#include "rlrun/envs/gripper/gripper_lift.hpp"

namespace rlrun {

// The action (dx, dy, dz, grip in [-1, 1]) for the env's current state.
std::array<float, 4> scripted_grasp_action(const GripperLift& env);

// As a policy acting on `env`. Throws UsageError unless the innermost env is a GripperLift.
std::function<void(const Eigen::MatrixXf& obs, Eigen::MatrixXf& action)> scripted_grasp_actions(
    Env& env);

}  // namespace rlrun
