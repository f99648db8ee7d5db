#pragma once
// MountainCarContinuous-v0: gymnasium/envs/classic_control/continuous_mountain_car.py
// (Gymnasium 1.0.0). Continuous force in [-1, 1]; +100 at the goal, -0.1 * a^2 every step.
#include <span>
#include <string>

#include "rlrun/envs/classic/classic_control_env.hpp"
#include "rlrun/envs/classic/mountain_car.hpp"

namespace rlrun {

// The state is position, velocity; Gymnasium keeps it as float64 after reset but as a float32
// array after every step (both are held as doubles here, rounded to float after each step).
class MountainCarContinuous : public ClassicControlEnv {
 public:
  using Config = MountainCarConfig;
  static constexpr int kMaxEpisodeSteps = 999;  // registered TimeLimit (gymnasium/envs/__init__.py)

  explicit MountainCarContinuous(const Config& config = {});
  StepResult step(std::span<const float> action, std::span<float> obs) override;

 private:
  Config config_;
};

}  // namespace rlrun
