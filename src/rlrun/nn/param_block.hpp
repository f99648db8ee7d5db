#pragma once
// A contiguous float tensor and its gradient, as an optimizer sees it (one entry of
// torch.optim's params list). Non-owning: the pointers stay valid only while the owner (an Mlp's
// params_/grads_, a ParamVector) is neither resized nor moved, so build optimizers after the
// networks are in their final place and rebind them (Adam::rebind) after copying an algorithm.
#include <Eigen/Core>

namespace rlrun {

struct ParamBlock {
  float* value = nullptr;
  float* grad = nullptr;
  Eigen::Index size = 0;
};

}  // namespace rlrun
