#include "rlrun/nn/rmsprop.hpp"

#include <utility>

#include "rlrun/nn/dense_kernels.hpp"

namespace rlrun {

RmsProp::RmsProp(std::vector<ParamBlock> blocks, RmsPropConfig cfg)
    : BlockOptimizer(std::move(blocks), "RmsProp"), cfg_(cfg), square_avg_(zero_state()) {}

void RmsProp::step(float lr) {
  ++steps_;
  const auto alpha = static_cast<float>(cfg_.alpha);
  const auto eps = static_cast<float>(cfg_.eps);
  // One fused pass per block on the CPU's widest vectors (dense_kernels.hpp).
  for (size_t i = 0; i < blocks_.size(); ++i) {
    const ParamBlock& b = blocks_[i];
    dense::rmsprop_update(b.size, b.value, b.grad, square_avg_[i].data(), alpha, lr, eps);
  }
}

}  // namespace rlrun
