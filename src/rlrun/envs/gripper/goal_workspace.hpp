#pragma once
// Where the goal tasks' grasp point may be sent (gripper_goal_env.hpp) and where their scenario
// files may put things (goal_scenario.hpp). panda-gym's ranges (a 30 cm square, goals up to
// 30 cm above the table) plus a 10 cm margin around the square, so the gripper can get behind
// a cube at the square's edge to push it inwards. The table top is z = 0.
namespace rlrun {

struct GoalWorkspace {
  static constexpr double kXY = 0.25;  // m: |x|, |y| of the grasp point (the drawn table)
  static constexpr double kBottom =
      0.018;                            // m: the finger tips (1.5 cm below) 3 mm above the table
  static constexpr double kTop = 0.35;  // m: above Reach's highest goal (0.3)
};

}  // namespace rlrun
