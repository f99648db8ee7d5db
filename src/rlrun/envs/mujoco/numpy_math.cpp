#include "rlrun/envs/mujoco/numpy_math.hpp"

#include <cmath>

namespace rlrun::mujoco {

double euclidean_norm(std::span<const double> v) {
  double dot = 0.0;
  for (double x : v) dot += x * x;
  return std::sqrt(dot);
}

double scalar_squared(double x) {
  // Read through volatile: the compiler may not assume 2.0 and rewrite the call as x * x.
  volatile double two = 2.0;
  return std::pow(x, two);
}

}  // namespace rlrun::mujoco
