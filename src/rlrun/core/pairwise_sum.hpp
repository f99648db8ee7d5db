#pragma once
// numpy's pairwise_sum (numpy/core/src/umath/loops_utils.h.src), which np.sum, np.mean and
// np.var use on a contiguous vector, in the array's own type (float32 arrays sum in float32): up
// to 8 values left to right, up to 128 in eight interleaved partial sums, beyond that halves
// summed recursively. Matching it makes rlrun's sums round as Gymnasium's and SB3's numpy code.
#include <cstddef>
#include <span>

namespace rlrun {

template <class T>
T pairwise_sum(std::span<const T> a) {
  const size_t n = a.size();
  if (n < 8) {
    T res = 0;
    for (T v : a) res += v;
    return res;
  }
  if (n <= 128) {
    T r[8];
    for (size_t j = 0; j < 8; ++j) r[j] = a[j];
    size_t i = 8;
    for (; i < n - (n % 8); i += 8)
      for (size_t j = 0; j < 8; ++j) r[j] += a[i + j];
    T res = ((r[0] + r[1]) + (r[2] + r[3])) + ((r[4] + r[5]) + (r[6] + r[7]));
    for (; i < n; ++i) res += a[i];
    return res;
  }
  size_t half = n / 2;
  half -= half % 8;
  return pairwise_sum(a.first(half)) + pairwise_sum(a.subspan(half));
}

}  // namespace rlrun
