#include "rlrun/envs/gripper/scripted_grasp_policy.hpp"

#include <algorithm>
#include <cmath>

#include "rlrun/core/errors.hpp"

namespace rlrun {

namespace {

constexpr double kAlignedXY = 0.006;  // m: close enough above the cube to descend
constexpr double kAtCube = 0.008;     // m: close enough to the cube's centre to close
constexpr double kClearance = 0.04;   // m above the cube's top while travelling
constexpr double kLiftTo = 0.08;      // m above the resting height (success needs 0.05)

float toward(double target, double at) {
  return static_cast<float>(std::clamp((target - at) / GripperLift::kMovePerStep, -1.0, 1.0));
}

}  // namespace

std::array<float, 4> scripted_grasp_action(const GripperLift& env) {
  const GripperWorld& w = env.world();
  const Vec3 cube = w.cube_position(), at = w.grasp_point();
  const auto touching = w.finger_contacts();
  const double size = w.layout().cube_size;
  const double dx = cube[0] - at[0], dy = cube[1] - at[1], dz = cube[2] - at[2];
  constexpr float kOpen = -1.0f, kClose = 1.0f;
  if (touching[0] && touching[1])  // holding it: lift, squeezing
    return {toward(cube[0], at[0]), toward(cube[1], at[1]),
            toward(env.resting_height() + kLiftTo, at[2]), kClose};
  if (std::sqrt(dx * dx + dy * dy + dz * dz) < kAtCube && w.opening() > size * 0.5)
    return {0.0f, 0.0f, 0.0f, kClose};  // around it: close
  if (w.opening() < size * 0.5)         // closed on nothing: open again, rise a little
    return {0.0f, 0.0f, 0.5f, kOpen};
  if (std::hypot(dx, dy) < kAlignedXY)  // above it: descend, open
    return {toward(cube[0], at[0]), toward(cube[1], at[1]), toward(cube[2], at[2]), kOpen};
  // Travel above the cube's top, then across.
  const double travel_height = cube[2] + size / 2 + kClearance;
  const bool low = at[2] < travel_height - 0.01;
  return {low ? 0.0f : toward(cube[0], at[0]), low ? 0.0f : toward(cube[1], at[1]),
          toward(travel_height, at[2]), kOpen};
}

std::function<void(const Eigen::MatrixXf&, Eigen::MatrixXf&)> scripted_grasp_actions(Env& env) {
  const auto* gripper = dynamic_cast<const GripperLift*>(&env.unwrapped());
  if (!gripper)
    throw UsageError(
        "the scripted policy is the grasp task's (GripperLift-v0, "
        "GripperLiftEasy-v0); this env is " +
        env.unwrapped().id());
  return [gripper](const Eigen::MatrixXf&, Eigen::MatrixXf& action) {
    const auto a = scripted_grasp_action(*gripper);
    action.resize(4, 1);
    for (int i = 0; i < 4; ++i) action(i, 0) = a[i];
  };
}

}  // namespace rlrun
