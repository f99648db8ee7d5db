#pragma once
// What Adam and RmsProp share: the parameter blocks they update (torch's param group), the step
// count torch keeps in their state, one state vector per block, and rebind().
#include <Eigen/Core>
#include <cstdint>
#include <utility>
#include <vector>

#include "rlrun/nn/param_block.hpp"

namespace rlrun {

class BlockOptimizer {
 public:
  // Points the optimizer at new storage of the same shapes (e.g. after copying the networks),
  // keeping its state and step count. Throws std::invalid_argument for other shapes.
  void rebind(std::vector<ParamBlock> blocks);

  const std::vector<ParamBlock>& blocks() const { return blocks_; }
  int64_t steps() const { return steps_; }
  void set_steps(int64_t steps) { steps_ = steps; }

 protected:
  BlockOptimizer() = default;
  // `name` (a literal) names the optimizer in rebind's errors.
  BlockOptimizer(std::vector<ParamBlock> blocks, const char* name)
      : blocks_(std::move(blocks)), name_(name) {}

  // One zero vector per block, the size of the block (torch's zeros_like state).
  std::vector<Eigen::VectorXf> zero_state() const;

  std::vector<ParamBlock> blocks_;
  int64_t steps_ = 0;

 private:
  const char* name_ = "BlockOptimizer";
};

}  // namespace rlrun
