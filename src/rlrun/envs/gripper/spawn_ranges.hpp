#pragma once
// What both kinds of gripper scenario file (grasp_scenario.hpp, goal_scenario.hpp) say about
// the cube and the gripper's start: [low, high] ranges under the same keys with the same
// meaning, drawn uniformly at every reset from the env's seeded stream (equal bounds: no
// randomisation). Each scenario gives its own defaults and bounds.
#include <vector>

namespace rlrun {

// The object: a cube resting on the table.
struct CubeRanges {
  std::vector<double> size;      // edge length, m
  std::vector<double> mass;      // kg
  std::vector<double> friction;  // Bullet friction coefficient
  std::vector<double> x, y;      // spawn position of its centre on the table, m
  std::vector<double> yaw;       // rad about the vertical

  template <class V>
  void visit(V& v) {
    v("cube_size", size, "[low, high] cube edge length in m");
    v("cube_mass", mass, "[low, high] cube mass in kg");
    v("cube_friction", friction, "[low, high] cube friction coefficient");
    v("cube_x", x, "[low, high] cube spawn x on the table, m");
    v("cube_y", y, "[low, high] cube spawn y on the table, m");
    v("cube_yaw", yaw, "[low, high] cube rotation about the vertical, rad");
  }
};

// Where the fingertips' centre (the grasp point) starts, m.
struct PalmRanges {
  std::vector<double> x, y, z;

  template <class V>
  void visit(V& v) {
    v("palm_x", x, "[low, high] start x of the fingertips' centre, m");
    v("palm_y", y, "[low, high] start y of the fingertips' centre, m");
    v("palm_z", z, "[low, high] start height of the fingertips' centre, m");
  }
};

}  // namespace rlrun
