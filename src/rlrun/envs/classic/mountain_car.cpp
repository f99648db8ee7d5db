#include "rlrun/envs/classic/mountain_car.hpp"

#include "rlrun/envs/classic/classic_render.hpp"

#include <algorithm>
#include <cmath>

namespace rlrun {

namespace {

constexpr double kGoalPosition = 0.5;
constexpr double kForce = 0.001;
constexpr double kGravity = 0.0025;

}  // namespace

bool mountain_car_initial_state(NumpyRandom& np_random, std::span<double> state) {
  state[0] = np_random.uniform(-0.6, -0.4);
  state[1] = 0.0;
  return false;
}

void mountain_car_observation(std::span<const double> state, std::span<float> obs) {
  obs[0] = static_cast<float>(state[0]);
  obs[1] = static_cast<float>(state[1]);
}

Space mountain_car_observation_space() {
  return Space::box(
      {static_cast<float>(kMountainCarMinPosition), static_cast<float>(-kMountainCarMaxSpeed)},
      {static_cast<float>(kMountainCarMaxPosition), static_cast<float>(kMountainCarMaxSpeed)});
}

// mountain_car.py: screen 600x400, render_fps 30; the picture is in mountain_car_render.cpp.
const ClassicSpec kMountainCar{"MountainCar-v0",
                               {600, 400, 30},
                               2,
                               false,
                               mountain_car_initial_state,
                               mountain_car_observation,
                               draw_mountain_car,
                               mountain_car_state_from_observation};

MountainCar::MountainCar(const Config& config)
    : ClassicControlEnv(kMountainCar, mountain_car_observation_space(), Space::discrete(3)),
      config_(config) {}

StepResult MountainCar::step(std::span<const float> action, std::span<float> obs) {
  require_reset();
  const int a = discrete_action(action);
  info_.clear();
  double& position = state_[0];
  double& velocity = state_[1];
  // Same operation order as mountain_car.py: velocity += (a - 1) * force + cos(3p) * (-g).
  velocity += (a - 1) * kForce + std::cos(3 * position) * (-kGravity);
  velocity = std::clamp(velocity, -kMountainCarMaxSpeed, kMountainCarMaxSpeed);
  position += velocity;
  position = std::clamp(position, kMountainCarMinPosition, kMountainCarMaxPosition);
  // Hitting the left wall is inelastic.
  if (position == kMountainCarMinPosition && velocity < 0) velocity = 0.0;

  const bool terminated = position >= kGoalPosition && velocity >= config_.goal_velocity;
  write_observation(obs);
  return {-1.0, terminated, false};
}

}  // namespace rlrun
