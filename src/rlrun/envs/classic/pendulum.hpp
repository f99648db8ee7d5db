#pragma once
// Pendulum-v1: gymnasium/envs/classic_control/pendulum.py (Gymnasium 1.0.0). Swing a
// frictionless pendulum up; torque clipped to [-2, 2], angular speed clipped to [-8, 8].
#include <cstdint>
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
  // sin(theta) of the last observation this step wrote, and the bits of that theta: the next
  // step's dynamics need the same sine, unless reset, set_state or a restore changed theta
  // since (then the bits differ and it is computed again). glibc's sin was 3 % of a PPO
  // Pendulum run. Starts as the pair (+0.0, sin(+0.0) = +0.0), true like every later one.
  double last_sin_theta_ = 0.0;
  uint64_t last_theta_bits_ = 0;
};

}  // namespace rlrun
