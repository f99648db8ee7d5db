#include "rlrun/envs/classic/mountain_car.hpp"

#include <algorithm>
#include <cmath>

namespace rlrun {

namespace {

constexpr double kMinPosition = -1.2;
constexpr double kMaxPosition = 0.6;
constexpr double kMaxSpeed = 0.07;
constexpr double kGoalPosition = 0.5;
constexpr double kForce = 0.001;
constexpr double kGravity = 0.0025;

}  // namespace

MountainCar::MountainCar(const Config& config)
    : ClassicControlEnv(
          Space::box({static_cast<float>(kMinPosition), static_cast<float>(-kMaxSpeed)},
                     {static_cast<float>(kMaxPosition), static_cast<float>(kMaxSpeed)}),
          Space::discrete(3)),
      config_(config) {}

StepResult MountainCar::step(std::span<const float> action, std::span<float> obs) {
  require_reset();
  const int a = discrete_action(action);
  info_.clear();
  // Same operation order as mountain_car.py: velocity += (a - 1) * force + cos(3p) * (-g).
  velocity_ += (a - 1) * kForce + std::cos(3 * position_) * (-kGravity);
  velocity_ = std::clamp(velocity_, -kMaxSpeed, kMaxSpeed);
  position_ += velocity_;
  position_ = std::clamp(position_, kMinPosition, kMaxPosition);
  // Hitting the left wall is inelastic.
  if (position_ == kMinPosition && velocity_ < 0) velocity_ = 0.0;

  const bool terminated = position_ >= kGoalPosition && velocity_ >= config_.goal_velocity;
  write_observation(obs);
  return {-1.0, terminated, false};
}

void MountainCar::sample_initial_state() {
  // np.array([np_random.uniform(low=-0.6, high=-0.4), 0])
  position_ = rng().uniform(-0.6, -0.4);
  velocity_ = 0.0;
}

void MountainCar::get_state(std::span<double> state) const {
  state[0] = position_;
  state[1] = velocity_;
}

void MountainCar::load_state(std::span<const double> state) {
  position_ = state[0];
  velocity_ = state[1];
}

void MountainCar::write_observation(std::span<float> obs) const {
  obs[0] = static_cast<float>(position_);
  obs[1] = static_cast<float>(velocity_);
}

}  // namespace rlrun
