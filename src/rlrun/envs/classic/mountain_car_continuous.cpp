#include "rlrun/envs/classic/mountain_car_continuous.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace rlrun {

namespace {

constexpr float kMinAction = -1.0f;
constexpr float kMaxAction = 1.0f;
constexpr double kMinPosition = -1.2;
constexpr double kMaxPosition = 0.6;
constexpr double kMaxSpeed = 0.07;
// 0.45 here (0.5 in the discrete MountainCar), after Arnaud de Broissia's version.
constexpr double kGoalPosition = 0.45;
constexpr double kPower = 0.0015;

}  // namespace

MountainCarContinuous::MountainCarContinuous(const Config& config)
    : ClassicControlEnv(
          Space::box({static_cast<float>(kMinPosition), static_cast<float>(-kMaxSpeed)},
                     {static_cast<float>(kMaxPosition), static_cast<float>(kMaxSpeed)}),
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
  double position = position_;
  double velocity = velocity_;
  velocity += force * kPower - 0.0025 * std::cos(3 * position);
  if (velocity > kMaxSpeed) velocity = kMaxSpeed;
  if (velocity < -kMaxSpeed) velocity = -kMaxSpeed;
  position += velocity;
  if (position > kMaxPosition) position = kMaxPosition;
  if (position < kMinPosition) position = kMinPosition;
  if (position == kMinPosition && velocity < 0) velocity = 0.0;

  const bool terminated = position >= kGoalPosition && velocity >= config_.goal_velocity;
  double reward = terminated ? 100.0 : 0.0;
  const double a = action[0];
  reward -= a * a * 0.1;  // math.pow(action[0], 2) * 0.1: unclipped, in float64

  // self.state = np.array([position, velocity], dtype=np.float32)
  position_ = static_cast<float>(position);
  velocity_ = static_cast<float>(velocity);
  state_is_float32_ = true;
  write_observation(obs);
  return {reward, terminated, false};
}

void MountainCarContinuous::sample_initial_state() {
  position_ = rng().uniform(-0.6, -0.4);
  velocity_ = 0.0;
  state_is_float32_ = false;
}

void MountainCarContinuous::get_state(std::span<double> state) const {
  state[0] = position_;
  state[1] = velocity_;
}

void MountainCarContinuous::load_state(std::span<const double> state) {
  position_ = state_is_float32_ ? static_cast<float>(state[0]) : state[0];
  velocity_ = state_is_float32_ ? static_cast<float>(state[1]) : state[1];
}

void MountainCarContinuous::write_observation(std::span<float> obs) const {
  obs[0] = static_cast<float>(position_);
  obs[1] = static_cast<float>(velocity_);
}

}  // namespace rlrun
