#include "rlrun/nn/split_adam.hpp"

#include <algorithm>
#include <cmath>

#include "rlrun/nn/batch_split.hpp"
#include "rlrun/nn/dense_kernels.hpp"

namespace rlrun {

namespace {
ParamBlock sub_block(const ParamBlock& b, const Part& part) {
  return {b.value + part.begin, b.grad + part.begin, part.count};
}

}  // namespace

SplitAdam::SplitAdam(ParamBlock block, AdamConfig config, ThreadPool* pool)
    : block_(block), pool_(pool) {
  for (int k = 0; k < 2; ++k)
    parts_[k] = Adam({sub_block(block_, param_part(block_.size, k))}, config);
}

double SplitAdam::grad_sum_of_squares() const {
  double sum_sq[2] = {0.0, 0.0};
  run_parts(pool_, 2, [&](int k) {
    const Part part = param_part(block_.size, k);
    sum_sq[k] = dense::sum_of_squares(part.count, block_.grad + part.begin);
  });
  return sum_sq[0] + sum_sq[1];
}

float SplitAdam::grad_norm() const { return static_cast<float>(std::sqrt(grad_sum_of_squares())); }

void SplitAdam::step(float lr, float grad_scale) {
  run_parts(pool_, 2, [&](int k) {
    const Part part = param_part(block_.size, k);
    if (grad_scale != 1.0f)
      Eigen::Map<Eigen::VectorXf>(block_.grad + part.begin, part.count) *= grad_scale;
    parts_[k].step(lr);
  });
}

}  // namespace rlrun
