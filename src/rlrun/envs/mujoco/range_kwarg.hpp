#pragma once
// A Gymnasium kwarg given as a (low, high) tuple of floats, such as Hopper-v4's
// healthy_z_range=(0.7, float("inf")) or Ant-v4's contact_force_range=(-1.0, 1.0). In YAML a list
// of two numbers with low <= high, where .inf and -.inf (YAML's spelling of infinity) leave a side
// unbounded:
//     kwargs: {healthy_z_range: [0.7, .inf]}
// Other settings refuse infinity (core/config_node.cpp); here it is the documented default.
// Gymnasium refuses nothing (low > high then lets no value through); rlrun refuses that too.
// Whether a bound counts is the task's rule: most test `min < value < max` (strictly_inside),
// Ant-v4 `min <= z <= max`, and Ant's contact forces are clipped to the range.
#include <yaml-cpp/yaml.h>

#include "rlrun/core/config_node.hpp"

namespace rlrun::mujoco {

struct RangeKwarg {
  double low = 0.0;
  double high = 0.0;
  // Gymnasium's `min < value < max`; false for NaN.
  bool strictly_inside(double value) const { return low < value && value < high; }
  bool operator==(const RangeKwarg&) const = default;
};

// Reads [low, high]: two numbers, .inf or -.inf, low <= high; anything else fails at its
// file:line:col.
void decode(const ConfigNode& n, RangeKwarg& out);
// Writes [low, high] in flow style, infinity as .inf / -.inf, so decode reads it back.
YAML::Node encode(const RangeKwarg& range);

}  // namespace rlrun::mujoco
