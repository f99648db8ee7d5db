#pragma once
// Pendulum-v1: gymnasium/envs/classic_control/pendulum.py (Gymnasium 1.0.0). Swing a
// frictionless pendulum up; torque clipped to [-2, 2], angular speed clipped to [-8, 8].
#include <limits>
#include <span>
#include <string>

#include "rlrun/envs/classic/classic_control_env.hpp"

namespace rlrun {

// gymnasium.make("Pendulum-v1", **kwargs) keyword arguments.
struct PendulumConfig {
  double g = 10.0;  // gravitational acceleration

  template <class V>
  void visit(V& v) {
    v("g", g, "gravity in m/s^2");
  }
};

// The state is theta (0 = upright; not wrapped, only the cost wraps it) and theta_dot. The last
// clipped torque is kept for the picture only (pendulum.py's self.last_u).
class Pendulum : public ClassicControlEnv {
 public:
  using Config = PendulumConfig;
  static constexpr int kMaxEpisodeSteps = 200;  // registered TimeLimit (gymnasium/envs/__init__.py)

  explicit Pendulum(const Config& config = {});
  StepResult step(std::span<const float> action, std::span<float> obs) override;

 private:
  Config config_;
};

}  // namespace rlrun
