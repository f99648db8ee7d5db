#pragma once
// torch.optim.RMSprop (Hinton, Coursera lecture 6e), non-centered, no momentum, no weight decay:
//   v = alpha v + (1 - alpha) g^2;  p -= lr g / (sqrt(v) + eps)
// v starts at zero and eps is added after the sqrt (torch/optim/rmsprop.py); TensorFlow's variant
// (v starts at one, eps inside the sqrt) is SB3's RMSpropTFLike, not the A2C default. SB3's A2C
// builds it with alpha = 0.99, eps = rms_prop_eps = 1e-5 (a2c/a2c.py), this struct's defaults.
#include <Eigen/Core>
#include <cstdint>
#include <vector>

#include "rlrun/nn/block_optimizer.hpp"

namespace rlrun {

// Doubles, like the Python floats torch receives (1 - alpha is formed in double).
struct RmsPropConfig {
  double alpha = 0.99;  // decay of the running average of squared gradients
  double eps = 1e-5;    // added to sqrt(v) in the denominator
};

class RmsProp : public BlockOptimizer {
 public:
  RmsProp() = default;
  explicit RmsProp(std::vector<ParamBlock> blocks, RmsPropConfig cfg = {});

  void step(float lr);

  const RmsPropConfig& config() const { return cfg_; }
  // Per-block running average of g^2 (torch's state square_avg).
  std::vector<Eigen::VectorXf>& square_avg() { return square_avg_; }
  const std::vector<Eigen::VectorXf>& square_avg() const { return square_avg_; }

 private:
  RmsPropConfig cfg_;
  std::vector<Eigen::VectorXf> square_avg_;
};

}  // namespace rlrun
