#pragma once
// What the MuJoCo task tests share besides ReferenceSim: random states and actions (actions
// also beyond the control range, which MuJoCo clamps while the control costs read them as
// given), the tests' own spelling of NumPy's arithmetic in the tasks' Python (written
// independently of rlrun's), and info lookup and checks.
#include <catch2/catch.hpp>
#include <cmath>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "rlrun/env.hpp"
#include "rlrun/info.hpp"
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

// init + U(-spread, spread) per entry: a state as a user would set one with set_state.
inline std::vector<double> around(std::span<const double> init, double spread, Rng& rng) {
  std::vector<double> out(init.begin(), init.end());
  for (double& v : out) v += rng.uniform(-spread, spread);
  return out;
}

// np.sum of a contiguous vector (numpy/core/src/umath/loops_utils.h.src, pairwise_sum): below 8
// values left to right; up to 128 in eight running sums, combined as a tree, then the rest left
// to right; longer ones split in halves (a multiple of 8). Compared with NumPy 1.24's np.sum on
// random float64 arrays of 14, 17 and 84 values (and float32 of 8): equal in every case.
template <class T>
T numpy_sum(std::span<const T> a) {
  if (a.size() < 8) {
    T sum = 0;
    for (T v : a) sum += v;
    return sum;
  }
  if (a.size() > 128) {
    size_t half = a.size() / 2;
    half -= half % 8;
    return numpy_sum(a.first(half)) + numpy_sum(a.subspan(half));
  }
  T r[8];
  for (size_t j = 0; j < 8; ++j) r[j] = a[j];
  size_t i = 8;
  for (; i + 8 <= a.size(); i += 8)
    for (size_t j = 0; j < 8; ++j) r[j] += a[i + j];
  T sum = ((r[0] + r[1]) + (r[2] + r[3])) + ((r[4] + r[5]) + (r[6] + r[7]));
  for (; i < a.size(); ++i) sum += a[i];
  return sum;
}

// np.sum(np.square(values)) in the values' own type.
template <class T>
T numpy_sum_of_squares(std::span<const T> values) {
  std::vector<T> squares;
  for (T v : values) squares.push_back(v * v);
  return numpy_sum<T>(squares);
}

// The env's info has exactly these keys, in this order, with these values (bit for bit).
inline void check_info(const Info& info,
                       const std::vector<std::pair<std::string, double>>& expected) {
  std::vector<std::string> names;
  for (const auto& [name, value] : expected) names.push_back(name);
  CHECK(info.keys() == names);
  for (const auto& [name, value] : expected) {
    INFO(name);
    REQUIRE(info.find(name) >= 0);
    CHECK(info.get(info.find(name)) == value);
  }
}

// np.sum(np.square(a)) of a float32 action, in float32.
inline float numpy_float32_sum_of_squares(std::span<const float> a) {
  return numpy_sum_of_squares<float>(a);
}

}  // namespace rlrun::testing
