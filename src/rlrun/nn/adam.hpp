#pragma once
// torch.optim.Adam (Kingma & Ba 2015) exactly as torch/optim/adam.py _single_tensor_adam does it
// (the CPU path; amsgrad, weight_decay and maximize off, as SB3 uses it):
//   m = lerp(m, g, 1 - beta1);  v = beta2 v + (1 - beta2) g^2
//   denom = sqrt(v) / sqrt(1 - beta2^t) + eps;  p -= (lr / (1 - beta1^t)) m / denom
// eps is added AFTER the bias-corrected sqrt, unlike the paper's Algorithm 1 with eps_hat.
// SB3's ActorCriticPolicy (PPO) passes eps = 1e-5 ("small values to avoid NaN in Adam");
// SAC/TD3/DQN use torch's default 1e-8, which is this struct's default.
#include <Eigen/Core>
#include <cstdint>
#include <vector>

#include "rlrun/nn/block_optimizer.hpp"

namespace rlrun {

// Doubles, like the Python floats torch receives: torch forms 1 - beta1 and 1 - beta2 in double
// before rounding them to float; from a float 0.999f, 1 - beta2 would be off by 5e-5 relative.
struct AdamConfig {
  double beta1 = 0.9;    // decay of the first-moment (mean) estimate
  double beta2 = 0.999;  // decay of the second-moment (uncentered variance) estimate
  double eps = 1e-8;     // added to the bias-corrected sqrt(v) in the denominator
};

class Adam : public BlockOptimizer {
 public:
  Adam() = default;
  explicit Adam(std::vector<ParamBlock> blocks, AdamConfig cfg = {});

  // One update of every block from its current gradient with learning rate lr (SB3 sets the
  // scheduled lr on the param groups before each optimizer.step()).
  void step(float lr);

  const AdamConfig& config() const { return cfg_; }
  // Per-block first and second moments (checkpointed as torch's state exp_avg / exp_avg_sq).
  std::vector<Eigen::VectorXf>& exp_avg() { return exp_avg_; }
  const std::vector<Eigen::VectorXf>& exp_avg() const { return exp_avg_; }
  std::vector<Eigen::VectorXf>& exp_avg_sq() { return exp_avg_sq_; }
  const std::vector<Eigen::VectorXf>& exp_avg_sq() const { return exp_avg_sq_; }

 private:
  AdamConfig cfg_;
  std::vector<Eigen::VectorXf> exp_avg_;
  std::vector<Eigen::VectorXf> exp_avg_sq_;
};

}  // namespace rlrun
