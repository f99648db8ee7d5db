#include "rlrun/envs/gripper/grasp_scenario.hpp"

#include <filesystem>

#include "rlrun/core/config_fields.hpp"
#include "rlrun/core/errors.hpp"
#include "rlrun/core/shipped_data.hpp"

namespace rlrun {

namespace fs = std::filesystem;

std::string shipped_grasp_scenario(const std::string& name) {
  return (fs::path(shipped_data_dir()) / "scenarios" / "grasp" / (name + ".yaml")).string();
}

GraspScenario load_grasp_scenario(const std::string& path) {
  const std::string file = find_data_file(path);
  if (!fs::exists(file)) throw RuntimeFailure("grasp scenario " + path + " does not exist");
  const ConfigNode root = ConfigNode::load_file(file);
  if (!root.is_map()) root.fail("a grasp scenario is a map (see scenarios/grasp/lift.yaml)");
  GraspScenario s;
  decode(root, s);
  const auto range = [&](const char* key, const std::vector<double>& r, bool positive) {
    if (r.size() != 2 || r[0] > r[1]) root.child(key).fail("expected [low, high] with low <= high");
    if (positive && r[0] <= 0) root.child(key).fail("must be > 0");
  };
  range("cube_size", s.cube.size, true);
  range("cube_mass", s.cube.mass, true);
  range("cube_friction", s.cube.friction, true);
  range("cube_x", s.cube.x, false);
  range("cube_y", s.cube.y, false);
  range("cube_yaw", s.cube.yaw, false);
  range("palm_x", s.palm.x, false);
  range("palm_y", s.palm.y, false);
  range("palm_z", s.palm.z, false);
  if (s.cube.size[1] > 0.08)
    root.child("cube_size").fail("the open gripper holds cubes up to 0.08 m");
  if (s.episode_steps < 1) root.child("episode_steps").fail("must be >= 1");
  return s;
}

}  // namespace rlrun
