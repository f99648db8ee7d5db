#include "rlrun/nn/rmsprop.hpp"

#include <stdexcept>
#include <utility>

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
  const auto w = static_cast<float>(1.0 - cfg_.alpha);
  const auto eps = static_cast<float>(cfg_.eps);
  for (size_t i = 0; i < blocks_.size(); ++i) {
    const ParamBlock& b = blocks_[i];
    Eigen::Map<Eigen::ArrayXf> p(b.value, b.size);
    const Eigen::Map<const Eigen::ArrayXf> g(b.grad, b.size);
    auto v = square_avg_[i].array();
    v = alpha * v + w * g.square();  // torch: square_avg.mul_(alpha).addcmul_(grad, grad, 1-alpha)
    p -= lr * g / (v.sqrt() + eps);
  }
}

}  // namespace rlrun
