#pragma once
// What the MuJoCo task tests share: random states and actions, numpy's sums written out
// independently of rlrun's, and the check that an env's info holds exactly the expected keys
// and values.
#include <catch2/catch.hpp>
#include <cmath>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "rlrun/info.hpp"
#include "rlrun/rng.hpp"

namespace rlrun::testing {

inline std::vector<float> random_action(Rng& rng, int n, double bound) {
  std::vector<float> a(static_cast<size_t>(n));
  for (float& v : a) v = static_cast<float>(rng.uniform(-bound, bound));
  return a;
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

}  // namespace rlrun::testing
