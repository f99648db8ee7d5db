#pragma once
// A Gymnasium kwarg given as a (low, high) tuple of floats, such as Hopper-v4's
// healthy_z_range=(0.7, float("inf")): the tasks test min < value < max (both strict), so it is
// an open interval. In YAML a list of two numbers with low <= high, where .inf and -.inf (YAML's
// spelling of infinity) leave a side unbounded:
//     kwargs: {healthy_z_range: [0.7, .inf]}
// Other settings refuse infinity (core/config_node.cpp); here it is the documented default.
#include <yaml-cpp/yaml.h>

#include "rlrun/core/config_node.hpp"

namespace rlrun::mujoco {

struct OpenInterval {
  double low = 0.0;
  double high = 0.0;
  // Gymnasium's `min < value < max`; false for NaN.
  bool contains(double value) const { return low < value && value < high; }
  bool operator==(const OpenInterval&) const = default;
};

// Reads [low, high]: two numbers, .inf or -.inf, low <= high; anything else fails at its
// file:line:col.
void decode(const ConfigNode& n, OpenInterval& out);
// Writes [low, high] in flow style, infinity as .inf / -.inf, so decode reads it back.
YAML::Node encode(const OpenInterval& interval);

}  // namespace rlrun::mujoco
