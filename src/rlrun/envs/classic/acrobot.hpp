#pragma once
// Acrobot-v1: gymnasium/envs/classic_control/acrobot.py (Gymnasium 1.0.0), Sutton's two-link
// under-actuated robot ("book" dynamics of Sutton & Barto 1998), integrated with one RK4 step
// of dt = 0.2 s. Torque noise is 0 as in Gymnasium, so the env draws randomness only in reset.
#include <array>
#include <span>
#include <string>

#include "rlrun/envs/classic/classic_control_env.hpp"

namespace rlrun {

// gymnasium.make("Acrobot-v1") takes no keyword arguments besides render_mode.
struct AcrobotConfig {
  template <class V>
  void visit(V&) {}
};

// The state is theta1, theta2, dtheta1, dtheta2. Gymnasium's state array is float32 right after
// reset() (`.astype(np.float32)`) and float64 after a step (rk4 returns float64).
class Acrobot : public ClassicControlEnv {
 public:
  using Config = AcrobotConfig;
  static constexpr int kMaxEpisodeSteps = 500;  // registered TimeLimit (gymnasium/envs/__init__.py)

  explicit Acrobot(const Config& config = {});
  StepResult step(std::span<const float> action, std::span<float> obs) override;
};

}  // namespace rlrun
