#include "rlrun/nn/adam.hpp"

#include <cmath>
#include <utility>

#include "rlrun/nn/dense_kernels.hpp"

namespace rlrun {

Adam::Adam(std::vector<ParamBlock> blocks, AdamConfig cfg)
    : BlockOptimizer(std::move(blocks), "Adam"),
      cfg_(cfg),
      exp_avg_(zero_state()),
      exp_avg_sq_(zero_state()) {}

void Adam::step(float lr) {
  ++steps_;
  // Scalars in double, as torch computes them from Python floats, then rounded once.
  const double t = static_cast<double>(steps_);
  const double bias_c1 = 1.0 - std::pow(cfg_.beta1, t);
  const double bias_c2 = 1.0 - std::pow(cfg_.beta2, t);
  const float step_size = static_cast<float>(lr / bias_c1);
  const float inv_bias_c2_sqrt = static_cast<float>(1.0 / std::sqrt(bias_c2));
  const dense::AdamCoefficients coefficients{
      .w1 = static_cast<float>(1.0 - cfg_.beta1),  // torch: exp_avg.lerp_(grad, 1 - beta1)
      .beta2 = static_cast<float>(cfg_.beta2),
      .w2 = static_cast<float>(1.0 - cfg_.beta2),
      .step_size = step_size,
      .inv_bias_c2_sqrt = inv_bias_c2_sqrt,
      .eps = static_cast<float>(cfg_.eps)};
  // One fused pass per block on the CPU's widest vectors (dense_kernels.hpp): with Eigen
  // expressions this ran 4 lanes wide in the portable build.
  for (size_t i = 0; i < blocks_.size(); ++i) {
    const ParamBlock& b = blocks_[i];
    dense::adam_update(b.size, b.value, b.grad, exp_avg_[i].data(), exp_avg_sq_[i].data(),
                       coefficients);
  }
}

}  // namespace rlrun
