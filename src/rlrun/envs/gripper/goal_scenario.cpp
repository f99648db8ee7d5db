#include "rlrun/envs/gripper/goal_scenario.hpp"

#include <cmath>
#include <filesystem>

#include "rlrun/core/config_fields.hpp"
#include "rlrun/core/errors.hpp"
#include "rlrun/core/float_format.hpp"
#include "rlrun/core/shipped_data.hpp"
#include "rlrun/envs/gripper/goal_workspace.hpp"

namespace rlrun {

namespace fs = std::filesystem;

GoalTaskScenario load_goal_task_scenario(const std::string& path) {
  const std::string file = find_data_file(path);
  if (!fs::exists(file)) throw RuntimeFailure("goal-task scenario " + path + " does not exist");
  const ConfigNode root = ConfigNode::load_file(file);
  if (!root.is_map()) root.fail("a goal-task scenario is a map (see scenarios/grasp/push.yaml)");
  GoalTaskScenario s;
  decode(root, s);
  // A problem is reported at its key when the file sets it, else at the file (a default that
  // another key made inconsistent).
  const auto at = [&](const char* key) { return root.has(key) ? root.child(key) : root; };
  const auto range = [&](const char* key, const std::vector<double>& r, double low, double high) {
    if (r.size() != 2 || !(r[0] <= r[1])) at(key).fail("expected [low, high] with low <= high");
    if (!(r[0] >= low && r[1] <= high))
      at(key).fail("must lie in [" + python_float_repr(low) + ", " + python_float_repr(high) + "]");
  };
  using W = GoalWorkspace;
  range("cube_size", s.cube.size, 0.01, 0.08);  // 0.08: the open gripper's reach
  range("cube_mass", s.cube.mass, 1e-3, 10.0);
  range("cube_friction", s.cube.friction, 1e-3, 10.0);
  const double half_cube = s.cube.size[1] / 2;
  range("cube_x", s.cube.x, -W::kXY + half_cube, W::kXY - half_cube);
  range("cube_y", s.cube.y, -W::kXY + half_cube, W::kXY - half_cube);
  range("cube_yaw", s.cube.yaw, -M_PI, M_PI);
  range("goal_x", s.goal_x, -W::kXY, W::kXY);
  range("goal_y", s.goal_y, -W::kXY, W::kXY);
  range("goal_z", s.goal_z, 0.0, W::kTop - s.cube.size[1] / 2);
  if (!(s.goal_in_air_probability >= 0 && s.goal_in_air_probability <= 1))
    at("goal_in_air_probability").fail("must be in [0, 1]");
  range("palm_x", s.palm.x, -W::kXY, W::kXY);
  range("palm_y", s.palm.y, -W::kXY, W::kXY);
  range("palm_z", s.palm.z, W::kBottom, W::kTop);
  if (s.episode_steps < 1) at("episode_steps").fail("must be >= 1");
  return s;
}

}  // namespace rlrun
