#include "rlrun/nn/clip_grad.hpp"

#include <cmath>

#include "rlrun/nn/dense_kernels.hpp"

namespace rlrun {

float grad_norm(std::span<const ParamBlock> blocks) {
  double sum_sq = 0.0;
  for (const ParamBlock& b : blocks) sum_sq += dense::sum_of_squares(b.size, b.grad);
  return static_cast<float>(std::sqrt(sum_sq));
}

float clip_grad_norm(std::span<const ParamBlock> blocks, float max_norm) {
  const float total = grad_norm(blocks);
  // torch: clip_coef = max_norm / (total_norm + 1e-6), clamped to at most 1, then always
  // multiplied in; multiplying by exactly 1 is a no-op, so we skip it.
  const float coef = max_norm / (total + 1e-6f);
  if (coef < 1.0f || std::isnan(coef)) {
    for (const ParamBlock& b : blocks) {
      Eigen::Map<Eigen::ArrayXf>(b.grad, b.size) *= coef;
    }
  }
  return total;
}

}  // namespace rlrun
