#pragma once
// Soft target update (SB3 common/utils.py polyak_update): target = (1 - tau) target + tau
// source, in place. tau = 1 copies (DQN's hard update).
#include <Eigen/Core>

namespace rlrun {

inline void polyak_update(const Eigen::VectorXf& source, Eigen::VectorXf& target, float tau) {
  if (tau == 1.0f) {
    target = source;
    return;
  }
  target = (1.0f - tau) * target + tau * source;
}

}  // namespace rlrun
