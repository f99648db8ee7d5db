#include "rlrun/nn/block_optimizer.hpp"

#include <stdexcept>
#include <string>
#include <utility>

namespace rlrun {

void BlockOptimizer::rebind(std::vector<ParamBlock> blocks) {
  if (blocks.size() != blocks_.size())
    throw std::invalid_argument(std::string(name_) + "::rebind: block count");
  for (size_t i = 0; i < blocks.size(); ++i) {
    if (blocks[i].size != blocks_[i].size)
      throw std::invalid_argument(std::string(name_) + "::rebind: block size");
  }
  blocks_ = std::move(blocks);
}

std::vector<Eigen::VectorXf> BlockOptimizer::zero_state() const {
  std::vector<Eigen::VectorXf> state;
  for (const ParamBlock& b : blocks_) state.push_back(Eigen::VectorXf::Zero(b.size));
  return state;
}

}  // namespace rlrun
