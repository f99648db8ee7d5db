#include "rlrun/envs/classic/mountain_car_continuous.hpp"

#include "rlrun/envs/classic/classic_render.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace rlrun {

namespace {

constexpr float kMinAction = -1.0f;
constexpr float kMaxAction = 1.0f;
// 0.45 here (0.5 in the discrete MountainCar), after Arnaud de Broissia's version.
constexpr double kGoalPosition = 0.45;
constexpr double kPower = 0.0015;

}  // namespace

// continuous_mountain_car.py: screen 600x400, render_fps 30; its state is float32 at times.
// The initial state is float64 (a float32 array only after the first step).
const ClassicSpec kMountainCarContinuous{"MountainCarContinuous-v0",
                                         {600, 400, 30},
                                         2,
                                         true,
                                         mountain_car_initial_state,
                                         mountain_car_observation,
                                         draw_mountain_car_continuous,
                                         mountain_car_state_from_observation};

MountainCarContinuous::MountainCarContinuous(const Config& config)
    : ClassicControlEnv(kMountainCarContinuous, mountain_car_observation_space(),
                        Space::box(kMinAction, kMaxAction, {1})),
      config_(config) {}

StepResult MountainCarContinuous::step(std::span<const float> action, std::span<float> obs) {
  require_reset();
  if (action.size() != 1)
    throw std::invalid_argument("MountainCarContinuous-v0: action must have 1 value");
  info_.clear();
  // The clipped action is the force; the reward below uses the raw action.
  const double force = std::min(std::max(action[0], kMinAction), kMaxAction);
  // Everything below runs in float64, including 3 * position on the float32 state. That is
  // NumPy 1.x scalar promotion (float32 scalar * Python number -> float64) and matches the
  // Gymnasium 1.0.0 reference trajectories bit for bit; NumPy 2 (NEP 50) would keep float32.
  double position = state_[0];
  double velocity = state_[1];
  velocity += force * kPower - 0.0025 * std::cos(3 * position);
  if (velocity > kMountainCarMaxSpeed) velocity = kMountainCarMaxSpeed;
  if (velocity < -kMountainCarMaxSpeed) velocity = -kMountainCarMaxSpeed;
  position += velocity;
  if (position > kMountainCarMaxPosition) position = kMountainCarMaxPosition;
  if (position < kMountainCarMinPosition) position = kMountainCarMinPosition;
  if (position == kMountainCarMinPosition && velocity < 0) velocity = 0.0;

  const bool terminated = position >= kGoalPosition && velocity >= config_.goal_velocity;
  double reward = terminated ? 100.0 : 0.0;
  const double a = action[0];
  reward -= a * a * 0.1;  // math.pow(action[0], 2) * 0.1: unclipped, in float64

  // self.state = np.array([position, velocity], dtype=np.float32)
  state_[0] = static_cast<float>(position);
  state_[1] = static_cast<float>(velocity);
  state_is_float32_ = true;
  write_observation(obs);
  return {reward, terminated, false};
}

}  // namespace rlrun
