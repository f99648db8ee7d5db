#pragma once
// What the MuJoCo task tests share besides ReferenceSim: random states and actions (actions
// also beyond the control range, which MuJoCo clamps while the control costs read them as
// given), the tests' own spelling of NumPy's arithmetic in the tasks' Python, and info lookup.
#include <catch2/catch.hpp>
#include <cmath>
#include <span>
#include <string>
#include <vector>

#include "rlrun/env.hpp"
#include "rlrun/rng.hpp"

namespace rlrun::testing {

inline std::vector<double> random_values(Rng& rng, size_t n, double low, double high) {
  std::vector<double> v(n);
  for (double& x : v) x = rng.uniform(low, high);
  return v;
}

// Each entry U(-bound, bound): bound > 1 reaches beyond a [-1, 1] control range.
inline std::vector<float> random_controls(Rng& rng, int n, double bound) {
  std::vector<float> a(static_cast<size_t>(n));
  for (float& v : a) v = static_cast<float>(rng.uniform(-bound, bound));
  return a;
}

// np.sum(np.square(a)) of a float32 action: float32 squares added in order (NumPy's pairwise
// sum adds fewer than 8 values one after the other; the tasks have at most 7 actuators).
inline float numpy_float32_sum_of_squares(std::span<const float> a) {
  REQUIRE(a.size() < 8);
  float sum = 0.0f;
  for (float v : a) sum += v * v;
  return sum;
}

// x ** 2 of a NumPy float64 scalar: the C library's pow(x, 2.0), which is not always x * x.
inline double numpy_scalar_pow2(double x) {
  volatile double two = 2.0;  // keeps the compiler from rewriting pow(x, 2.0) as x * x
  return std::pow(x, two);
}

// np.linalg.norm(v) of a 1-D float64 array: sqrt of the products added left to right (BLAS ddot).
inline double numpy_norm(std::span<const double> v) {
  double dot = 0.0;
  for (double x : v) dot += x * x;
  return std::sqrt(dot);
}

inline double info_value(const Env& env, const std::string& key) {
  const int index = env.info().find(key);
  INFO(key);
  REQUIRE(index >= 0);
  return env.info().get(index);
}

}  // namespace rlrun::testing
