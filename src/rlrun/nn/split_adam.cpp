#include "rlrun/nn/split_adam.hpp"

#include <algorithm>
#include <cmath>

#include "rlrun/nn/batch_split.hpp"

namespace rlrun {

namespace {
ParamBlock sub_block(const ParamBlock& b, const Part& part) {
  return {b.value + part.begin, b.grad + part.begin, part.count};
}

// Sum of squares in float chunks (vectorised) accumulated in double: the clipping coefficient
// needs no more (torch itself reduces in float32).
double sum_of_squares(const float* g, Eigen::Index n) {
  constexpr Eigen::Index kChunk = 4096;
  double sum = 0.0;
  for (Eigen::Index i = 0; i < n; i += kChunk)
    sum += Eigen::Map<const Eigen::VectorXf>(g + i, std::min(kChunk, n - i)).squaredNorm();
  return sum;
}
}  // namespace

SplitAdam::SplitAdam(ParamBlock block, AdamConfig config, ForkJoin* fork_join)
    : block_(block), fork_join_(fork_join) {
  for (int k = 0; k < 2; ++k)
    parts_[k] = Adam({sub_block(block_, param_part(block_.size, k))}, config);
}

float SplitAdam::grad_norm() const {
  double sum_sq[2] = {0.0, 0.0};
  run_parts(fork_join_, 2, [&](int k) {
    const Part part = param_part(block_.size, k);
    sum_sq[k] = sum_of_squares(block_.grad + part.begin, part.count);
  });
  return static_cast<float>(std::sqrt(sum_sq[0] + sum_sq[1]));
}

void SplitAdam::step(float lr, float grad_scale) {
  run_parts(fork_join_, 2, [&](int k) {
    const Part part = param_part(block_.size, k);
    if (grad_scale != 1.0f)
      Eigen::Map<Eigen::VectorXf>(block_.grad + part.begin, part.count) *= grad_scale;
    parts_[k].step(lr);
  });
}

}  // namespace rlrun
