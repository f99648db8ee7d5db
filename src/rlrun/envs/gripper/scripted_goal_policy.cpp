#include "rlrun/envs/gripper/scripted_goal_policy.hpp"

#include <algorithm>
#include <cmath>

#include "rlrun/core/errors.hpp"
#include "rlrun/envs/gripper/goal_workspace.hpp"

namespace rlrun {

namespace {

// Push.
constexpr double kPushHeight = 0.022;  // m: grasp point while pushing (finger tips 7 mm up)
constexpr double kBehindGap = 0.012;   // m between the fingers and the cube before a push
constexpr double kOnLine = 0.012;      // m off the push line still counted as behind it
constexpr double kPushStep = 0.02;     // m per step at most while pushing
// PickAndPlace.
constexpr double kAlignedXY = 0.006;  // m: close enough above the cube to descend
constexpr double kAtCube = 0.008;     // m: close enough to the cube's centre to close
constexpr double kCarryLift = 0.03;   // m above the table the cube is carried at, at least
// Both.
constexpr double kClearance = 0.04;  // m above the cube's top while travelling

float toward(double target, double at, double max_step = GripperGoalEnv::kMovePerStep) {
  const double move = std::clamp(target - at, -max_step, max_step);
  return static_cast<float>(move / GripperGoalEnv::kMovePerStep);
}

std::array<float, 4> move_to(const Vec3& target, const Vec3& at, float grip = 0.0f) {
  return {toward(target[0], at[0]), toward(target[1], at[1]), toward(target[2], at[2]), grip};
}

std::array<float, 4> reach(const GripperGoalEnv& env) {
  return move_to(env.goal(), env.world().grasp_point());
}

std::array<float, 4> push(const GripperGoalEnv& env) {
  const GripperWorld& w = env.world();
  const Vec3 cube = w.cube_position(), at = w.grasp_point(), goal = env.goal();
  const double half = w.layout().cube_size / 2;
  double ux = goal[0] - cube[0], uy = goal[1] - cube[1];
  const double left = std::hypot(ux, uy);
  if (left < 1e-9) return {0, 0, 0, 0};
  ux /= left;
  uy /= left;
  // The closed fingers are a 1 x 3 cm block (x by y); its extent towards the push.
  const double support =
      GripperWorld::kFingerHalf[0] * std::abs(ux) + GripperWorld::kFingerHalf[1] * std::abs(uy);
  const double standoff = half + support + kBehindGap;
  const double rel_x = at[0] - cube[0], rel_y = at[1] - cube[1];
  const double along = rel_x * ux + rel_y * uy, across = -rel_x * uy + rel_y * ux;
  const bool low = at[2] < kPushHeight + 0.01;
  if (low && along < -(half + support) + 0.01 && std::abs(across) < kOnLine) {
    // Behind it: push towards where the fingers end when the cube sits on the goal, a point
    // on the line through the cube, which also steers the fingers back onto that line.
    const double end_x = goal[0] - ux * (half + support), end_y = goal[1] - uy * (half + support);
    return {toward(end_x, at[0], kPushStep), toward(end_y, at[1], kPushStep),
            toward(kPushHeight, at[2]), 0.0f};
  }
  const Vec3 behind{cube[0] - ux * standoff, cube[1] - uy * standoff, kPushHeight};
  const double travel = cube[2] + half + kClearance;
  const double off = std::hypot(at[0] - behind[0], at[1] - behind[1]);
  if (off < 0.006) return move_to(behind, at);  // above the start of the push: descend
  if (at[2] < travel - 0.01) {
    // Low but not behind it: slide over if on the right side and close, else rise first.
    if (off < 0.02 && along < -(half + support)) return move_to(behind, at);
    return {0.0f, 0.0f, toward(travel, at[2]), 0.0f};
  }
  return move_to({behind[0], behind[1], travel}, at);
}

std::array<float, 4> pick_and_place(const GripperGoalEnv& env) {
  const GripperWorld& w = env.world();
  const Vec3 cube = w.cube_position(), at = w.grasp_point(), goal = env.goal();
  const auto touching = w.finger_contacts();
  const double size = w.layout().cube_size;
  constexpr float kOpen = 1.0f, kClose = -1.0f;  // panda-gym: +1 widens the fingers
  if (touching[0] && touching[1]) {
    // Holding it: lift clear of the table, then carry; the grasp point keeps the cube's offset.
    const Vec3 offset{at[0] - cube[0], at[1] - cube[1], at[2] - cube[2]};
    const bool far = std::hypot(goal[0] - cube[0], goal[1] - cube[1]) > 0.02;
    const double height = far ? std::max(goal[2], env.resting_height() + kCarryLift) : goal[2];
    const bool lifted = cube[2] > env.resting_height() + kCarryLift - 0.01 || !far;
    const Vec3 target{lifted ? goal[0] : cube[0], lifted ? goal[1] : cube[1], height};
    return move_to({target[0] + offset[0], target[1] + offset[1], target[2] + offset[2]}, at,
                   kClose);
  }
  const double dx = cube[0] - at[0], dy = cube[1] - at[1], dz = cube[2] - at[2];
  const bool near = std::hypot(dx, dy) < kAlignedXY;
  if (near && std::sqrt(dx * dx + dy * dy + dz * dz) < kAtCube && w.opening() > size * 0.7)
    return {0.0f, 0.0f, 0.0f, kClose};   // around it: close
  if (near && w.opening() < size * 0.7)  // closed on nothing (or not yet open): open, rise
    return {0.0f, 0.0f, toward(cube[2] + size, at[2]), kOpen};
  if (near)  // above it, open: descend
    return move_to(cube, at, kOpen);
  // Travel above the cube's top, then across, opening on the way.
  const double travel_height = cube[2] + size / 2 + kClearance;
  const bool low = at[2] < travel_height - 0.01;
  return {low ? 0.0f : toward(cube[0], at[0]), low ? 0.0f : toward(cube[1], at[1]),
          toward(travel_height, at[2]), kOpen};
}

}  // namespace

std::array<float, 4> scripted_goal_action(const GripperGoalEnv& env) {
  switch (env.task()) {
    case GoalTask::kReach: return reach(env);
    case GoalTask::kPush: return push(env);
    case GoalTask::kPickAndPlace: return pick_and_place(env);
  }
  return {0, 0, 0, 0};
}

std::function<void(const Eigen::MatrixXf&, Eigen::MatrixXf&)> scripted_goal_actions(Env& env) {
  const auto* task = dynamic_cast<const GripperGoalEnv*>(&env.unwrapped());
  if (!task)
    throw UsageError(
        "the scripted policy is the goal tasks' (GripperReach-v0, GripperPush-v0, "
        "GripperPickAndPlace-v0); this env is " +
        env.unwrapped().id());
  return [task](const Eigen::MatrixXf&, Eigen::MatrixXf& action) {
    const auto a = scripted_goal_action(*task);
    const int n = task->action_space().flat_dim();
    action.resize(n, 1);
    for (int i = 0; i < n; ++i) action(i, 0) = a[i];
  };
}

}  // namespace rlrun
