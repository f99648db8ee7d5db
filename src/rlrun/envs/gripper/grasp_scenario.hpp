#pragma once
// A grasp scenario file (scenarios/grasp/*.yaml): the object, where things start, how much the
// world is randomised per episode, and how long an episode lasts. GripperLift-v0 reads
// scenarios/grasp/lift.yaml, GripperLiftEasy-v0 scenarios/grasp/lift_easy.yaml; `scenario:`
// in env.kwargs names another. Ranges are [low, high], drawn uniformly at every reset from the
// env's seeded stream (equal bounds: no randomisation). Unknown keys are errors with
// file:line:column and the closest valid key.
#include <string>
#include <vector>

namespace rlrun {

struct GraspScenario {
  std::string name;
  std::string description;
  // The object (a cube; domain randomisation through the ranges).
  std::vector<double> cube_size{0.05, 0.05};      // edge length, m
  std::vector<double> cube_mass{0.1, 0.1};        // kg
  std::vector<double> cube_friction{1.0, 1.0};    // Bullet friction coefficient
  std::vector<double> cube_x{-0.1, 0.1};          // spawn position on the table, m
  std::vector<double> cube_y{-0.1, 0.1};
  std::vector<double> cube_yaw{-0.3, 0.3};        // rad about the vertical
  // Where the fingertips' centre starts: absolute, or above the cube (palm_above_cube).
  bool palm_above_cube = false;
  std::vector<double> palm_x{-0.1, 0.1};          // m (relative to the cube if palm_above_cube)
  std::vector<double> palm_y{-0.1, 0.1};
  std::vector<double> palm_z{0.12, 0.18};         // height above the table (or the cube's top)
  int episode_steps = 50;                         // decisions per episode (then truncated)

  template <class V>
  void visit(V& v) {
    v("name", name, "the scenario's name");
    v("description", description, "what it is for");
    v("cube_size", cube_size, "[low, high] cube edge length in m");
    v("cube_mass", cube_mass, "[low, high] cube mass in kg");
    v("cube_friction", cube_friction, "[low, high] cube friction coefficient");
    v("cube_x", cube_x, "[low, high] cube spawn x on the table, m");
    v("cube_y", cube_y, "[low, high] cube spawn y on the table, m");
    v("cube_yaw", cube_yaw, "[low, high] cube rotation about the vertical, rad");
    v("palm_above_cube", palm_above_cube,
      "palm_x/palm_y are offsets from the cube and palm_z the height above its top");
    v("palm_x", palm_x, "[low, high] start x of the fingertips' centre, m");
    v("palm_y", palm_y, "[low, high] start y of the fingertips' centre, m");
    v("palm_z", palm_z, "[low, high] start height of the fingertips' centre, m");
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
