#pragma once
// A kwarg that Gymnasium's MuJoCo tasks take as a tuple (low, high), such as Ant-v4's
// healthy_z_range=(0.2, 1.0) or contact_force_range=(-1.0, 1.0): in rlrun's YAML a list of two
// numbers, `healthy_z_range: [0.2, 1.0]`. A bound may be infinite, as Gymnasium's float("inf")
// makes it (`[0.2, .inf]`: no upper bound), which rlrun's other settings refuse
// (ConfigNode::as_double). Refused: another count of numbers, NaN, and low > high (numpy's
// clip and Gymnasium's `low <= z <= high` would then never let a value through).
#include <yaml-cpp/yaml.h>

#include "rlrun/core/config_node.hpp"

namespace rlrun::mujoco {

struct RangeKwarg {
  double low = 0.0;
  double high = 0.0;
  bool operator==(const RangeKwarg&) const = default;
};

// Found by argument-dependent lookup from the config reader and writer (core/config_fields.hpp).
void decode(const ConfigNode& n, RangeKwarg& out);
YAML::Node encode(const RangeKwarg& v);  // [low, high], an infinite bound as .inf / -.inf

}  // namespace rlrun::mujoco
