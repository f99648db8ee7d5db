#pragma once
// Hand-written controllers for the goal tasks (`--policy scripted` / `--baseline scripted` in
// eval and record), one per task, reading the simulated world like scripted_grasp_policy.hpp
// and keeping no memory (each action follows from the state):
//   Reach         move the grasp point straight to the goal;
//   Push          go (above the cube) to the point behind it on the line from the goal through
//                 the cube, descend to the table and push along that line, steering back onto
//                 it; rise and go round again when the cube has turned away;
//   PickAndPlace  open, go above the cube, descend, close, lift and carry it to the goal.
// They show that each task is solvable with the env's actions and forces.
#include <Eigen/Core>
#include <array>
#include <functional>

#include "rlrun/env.hpp"
#include "rlrun/envs/gripper/gripper_goal_env.hpp"

namespace rlrun {

// The action for the env's current state (the first 3 entries for Reach and Push; dx, dy,
// dz, and for PickAndPlace the opening change, +1 opens).
std::array<float, 4> scripted_goal_action(const GripperGoalEnv& env);

// As a policy acting on `env`. Throws UsageError unless the innermost env is a goal task.
std::function<void(const Eigen::MatrixXf& obs, Eigen::MatrixXf& action)> scripted_goal_actions(
    Env& env);

}  // namespace rlrun
