#include "rlrun/nn/rmsprop.hpp"

#include <stdexcept>
#include <utility>

#include "rlrun/nn/dense_kernels.hpp"

namespace rlrun {

RmsProp::RmsProp(std::vector<ParamBlock> blocks, RmsPropConfig cfg)
    : blocks_(std::move(blocks)), cfg_(cfg) {
  for (const ParamBlock& b : blocks_) square_avg_.push_back(Eigen::VectorXf::Zero(b.size));
}

void RmsProp::rebind(std::vector<ParamBlock> blocks) {
  if (blocks.size() != blocks_.size()) throw std::invalid_argument("RmsProp::rebind: block count");
  for (size_t i = 0; i < blocks.size(); ++i) {
    if (blocks[i].size != blocks_[i].size) {
      throw std::invalid_argument("RmsProp::rebind: block size");
    }
  }
  blocks_ = std::move(blocks);
}

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
