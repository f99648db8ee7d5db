#pragma once
// A goal-task scenario file (scenarios/grasp/{reach,push,pick_and_place}.yaml): where the cube
// and the gripper start, where goals are drawn, and how long an episode lasts, for
// GripperReach-v0, GripperPush-v0 and GripperPickAndPlace-v0 (gripper_goal_env.hpp). The
// defaults are panda-gym's (panda_gym/envs/tasks/{reach,push,pick_and_place}.py): a 4 cm cube
// anywhere on a 30 cm square, goals on a 30 cm square. Coordinates are the world's: the table
// top is z = 0, the square is centred on the origin. Ranges are [low, high], drawn uniformly at
// every reset from the env's seeded stream (equal bounds: no randomisation). Unknown keys are
// errors with file:line:column and the closest valid key.
#include <string>
#include <vector>

#include "rlrun/envs/gripper/spawn_ranges.hpp"

namespace rlrun {

struct GoalTaskScenario {
  std::string name;
  std::string description;
  // The object (Push, PickAndPlace; Reach has none and ignores these). panda-gym: a 4 cm cube
  // placed unturned.
  CubeRanges cube{.size = {0.04, 0.04},
                  .mass = {0.1, 0.1},
                  .friction = {1.0, 1.0},
                  .x = {-0.15, 0.15},
                  .y = {-0.15, 0.15},
                  .yaw = {0.0, 0.0}};
  // The goal. Reach: the grasp point's target, goal_z its height above the table. Push,
  // PickAndPlace: the cube centre's target, goal_z its height above the cube's resting height.
  std::vector<double> goal_x{-0.15, 0.15};
  std::vector<double> goal_y{-0.15, 0.15};
  std::vector<double> goal_z{0.0, 0.0};
  // Probability that goal_z is drawn at a reset; otherwise it is goal_z's low bound (on the
  // table). Gymnasium-Robotics FetchPickAndPlace's target_in_the_air: 0.5.
  double goal_in_air_probability = 1.0;
  // Redraw the goal while the achieved goal at the start (the cube, or the grasp point for
  // Reach) is already within the env's distance_threshold of it, so no episode starts solved.
  // panda-gym draws the two independently (false).
  bool goal_apart = false;
  // Where the fingertips' centre (grasp point) starts, m above the table for z.
  PalmRanges palm{.x = {0.0, 0.0}, .y = {0.0, 0.0}, .z = {0.2, 0.2}};
  int episode_steps = 50;  // decisions per episode (then truncated); panda-gym: 50

  template <class V>
  void visit(V& v) {
    v("name", name, "the scenario's name");
    v("description", description, "what it is for");
    cube.visit(v);
    v("goal_x", goal_x, "[low, high] goal x, m");
    v("goal_y", goal_y, "[low, high] goal y, m");
    v("goal_z", goal_z,
      "[low, high] goal height, m: above the table (Reach) or the cube's resting height");
    v("goal_in_air_probability", goal_in_air_probability,
      "probability that goal_z is drawn (else its low bound)");
    v("goal_apart", goal_apart, "redraw goals the start already reaches");
    palm.visit(v);
    v("episode_steps", episode_steps, "decisions per episode (truncated after)");
  }
};

// Reads and checks a goal-task scenario (ranges of two numbers with low <= high, sizes and
// masses > 0, a cube the open gripper holds, a probability in [0, 1], everything inside the
// gripper's workspace). A relative path that does not exist from the working directory is
// looked for in rlrun's shipped data. Throws ConfigError / RuntimeFailure.
GoalTaskScenario load_goal_task_scenario(const std::string& path);

}  // namespace rlrun
