#include "rlrun/envs/classic/pendulum.hpp"

#include "rlrun/envs/classic/classic_render.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>

namespace rlrun {

namespace {

constexpr double kMaxSpeed = 8.0;
constexpr float kMaxTorque = 2.0f;
constexpr double kDt = 0.05;
constexpr double kMass = 1.0;
constexpr double kLength = 1.0;
// Reset ranges: theta ~ U(-pi, pi), theta_dot ~ U(-1, 1) (DEFAULT_X, DEFAULT_Y).
constexpr double kResetTheta = std::numbers::pi;
constexpr double kResetThetaDot = 1.0;

// pendulum.py angle_normalize: maps to [-pi, pi) with Python's floored modulo.
double angle_normalize(double x) {
  constexpr double kTwoPi = 2 * std::numbers::pi;
  const double shifted = x + std::numbers::pi;
  // Within one turn the remainder is the number itself, exactly (fmod is exact too): skip the
  // libm call, 1 % of a PPO Pendulum run.
  double r = shifted >= 0.0 && shifted < kTwoPi ? shifted : std::fmod(shifted, kTwoPi);
  if (r != 0.0 && r < 0.0) r += kTwoPi;  // Python's % takes the sign of the divisor
  return r - std::numbers::pi;
}

// theta ~ U(-pi, pi), theta_dot ~ U(-1, 1) (DEFAULT_X, DEFAULT_Y).
bool initial_state(NumpyRandom& np_random, std::span<double> state) {
  state[0] = np_random.uniform(-kResetTheta, kResetTheta);
  state[1] = np_random.uniform(-kResetThetaDot, kResetThetaDot);
  return false;
}

// cos(theta), sin(theta), theta_dot in float32; returns sin(theta) in float64.
double observe(std::span<const double> state, std::span<float> obs) {
  const double sin_theta = std::sin(state[0]);
  obs[0] = static_cast<float>(std::cos(state[0]));
  obs[1] = static_cast<float>(sin_theta);
  obs[2] = static_cast<float>(state[1]);
  return sin_theta;
}

void observation(std::span<const double> state, std::span<float> obs) { observe(state, obs); }

}  // namespace

// pendulum.py: screen_dim 500, render_fps 30; the picture is in pendulum_render.cpp.
const ClassicSpec kPendulum{"Pendulum-v1",
                            {500, 500, 30},
                            2,
                            false,
                            initial_state,
                            observation,
                            draw_pendulum,
                            pendulum_state_from_observation};

Pendulum::Pendulum(const Config& config)
    : ClassicControlEnv(kPendulum,
                        Space::box({-1.0f, -1.0f, static_cast<float>(-kMaxSpeed)},
                                   {1.0f, 1.0f, static_cast<float>(kMaxSpeed)}),
                        Space::box(-kMaxTorque, kMaxTorque, {1})),
      config_(config) {}

StepResult Pendulum::step(std::span<const float> action, std::span<float> obs) {
  require_reset();
  if (action.size() != 1) throw std::invalid_argument("Pendulum-v1: action must have 1 value");
  info_.clear();
  // The clipped torque enters the dynamics and the cost in float64: that matches the
  // Gymnasium reference to the last bit, rounding 3 * u or u * u to float32 (what NumPy 2
  // does with a float32 action) does not.
  const double u = std::clamp(action[0], -kMaxTorque, kMaxTorque);
  const double g = config_.g;
  double& theta = state_[0];
  double& theta_dot = state_[1];

  const double th_norm = angle_normalize(theta);
  const double costs = th_norm * th_norm + 0.1 * (theta_dot * theta_dot) + 0.001 * (u * u);

  const double sin_theta =
      std::bit_cast<uint64_t>(theta) == last_theta_bits_ ? last_sin_theta_ : std::sin(theta);
  double new_theta_dot =
      theta_dot + (3 * g / (2 * kLength) * sin_theta + 3.0 / (kMass * kLength * kLength) * u) * kDt;
  new_theta_dot = std::clamp(new_theta_dot, -kMaxSpeed, kMaxSpeed);
  theta = theta + new_theta_dot * kDt;
  theta_dot = new_theta_dot;
  last_action_ = u;  // for the picture only

  last_sin_theta_ = observe(std::span<const double>(state_.data(), 2), obs);
  last_theta_bits_ = std::bit_cast<uint64_t>(theta);
  return {-costs, false, false};
}

}  // namespace rlrun
