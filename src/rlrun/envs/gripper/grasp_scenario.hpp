#pragma once
// A grasp scenario file (scenarios/grasp/*.yaml): the object, where things start, how much the
// world is randomised per episode, and how long an episode lasts. GripperLift-v0 reads
// scenarios/grasp/lift.yaml, GripperLiftEasy-v0 scenarios/grasp/lift_easy.yaml; `scenario:`
// in env.kwargs names another. Ranges are [low, high], drawn uniformly at every reset from the
// env's seeded stream (equal bounds: no randomisation). Unknown keys are errors with
// file:line:column and the closest valid key.
#include <string>

#include "rlrun/envs/gripper/spawn_ranges.hpp"

namespace rlrun {

struct GraspScenario {
  std::string name;
  std::string description;
  // The object (a cube; domain randomisation through the ranges).
  CubeRanges cube{.size = {0.05, 0.05},
                  .mass = {0.1, 0.1},
                  .friction = {1.0, 1.0},
                  .x = {-0.1, 0.1},
                  .y = {-0.1, 0.1},
                  .yaw = {-0.3, 0.3}};
  // Where the fingertips' centre starts: absolute, or above the cube (palm_above_cube): then
  // palm x and y are relative to the cube and z is the height above its top.
  bool palm_above_cube = false;
  PalmRanges palm{.x = {-0.1, 0.1}, .y = {-0.1, 0.1}, .z = {0.12, 0.18}};
  int episode_steps = 50;  // decisions per episode (then truncated)

  template <class V>
  void visit(V& v) {
    v("name", name, "the scenario's name");
    v("description", description, "what it is for");
    cube.visit(v);
    v("palm_above_cube", palm_above_cube,
      "palm_x/palm_y are offsets from the cube and palm_z the height above its top");
    palm.visit(v);
    v("episode_steps", episode_steps, "decisions per episode (truncated after)");
  }
};

// The shipped scenarios: scenarios/grasp/<name>.yaml in shipped_data_dir().
std::string shipped_grasp_scenario(const std::string& name);

// Reads and checks a scenario (ranges of two numbers, low <= high, sizes and masses > 0, a
// cube small enough for the open gripper). A relative path that does not exist from the
// working directory is looked for in rlrun's shipped data (find_data_file). Throws
// ConfigError / RuntimeFailure.
GraspScenario load_grasp_scenario(const std::string& path);

}  // namespace rlrun
