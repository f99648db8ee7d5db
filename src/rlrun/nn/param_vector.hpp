#pragma once
// A free-standing learnable vector with its gradient, e.g. PPO's state-independent log_std
// (SB3 DiagGaussianDistribution.proba_distribution_net: nn.Parameter(ones(action_dim) *
// log_std_init)) or SAC's log_ent_coef.
#include <Eigen/Core>

#include "rlrun/nn/param_block.hpp"

namespace rlrun {

struct ParamVector {
  Eigen::VectorXf value;
  Eigen::VectorXf grad;

  ParamVector() = default;
  ParamVector(Eigen::Index size, float init)
      : value(Eigen::VectorXf::Constant(size, init)), grad(Eigen::VectorXf::Zero(size)) {}

  ParamBlock block() { return {value.data(), grad.data(), value.size()}; }
  void zero_grad() { grad.setZero(); }
};

}  // namespace rlrun
