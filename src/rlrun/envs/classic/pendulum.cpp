#include "rlrun/envs/classic/pendulum.hpp"

#include <algorithm>
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
  double r = std::fmod(x + std::numbers::pi, kTwoPi);
  if (r != 0.0 && r < 0.0) r += kTwoPi;  // Python's % takes the sign of the divisor
  return r - std::numbers::pi;
}

}  // namespace

Pendulum::Pendulum(const Config& config)
    : ClassicControlEnv(Space::box({-1.0f, -1.0f, static_cast<float>(-kMaxSpeed)},
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

  const double th_norm = angle_normalize(theta_);
  const double costs = th_norm * th_norm + 0.1 * (theta_dot_ * theta_dot_) + 0.001 * (u * u);

  double new_theta_dot =
      theta_dot_ +
      (3 * g / (2 * kLength) * std::sin(theta_) + 3.0 / (kMass * kLength * kLength) * u) * kDt;
  new_theta_dot = std::clamp(new_theta_dot, -kMaxSpeed, kMaxSpeed);
  theta_ = theta_ + new_theta_dot * kDt;
  theta_dot_ = new_theta_dot;
  last_u_ = u;  // for rendering only

  write_observation(obs);
  return {-costs, false, false};
}

void Pendulum::sample_initial_state() {
  theta_ = rng().uniform(-kResetTheta, kResetTheta);
  theta_dot_ = rng().uniform(-kResetThetaDot, kResetThetaDot);
  last_u_ = std::numeric_limits<double>::quiet_NaN();
}

void Pendulum::get_state(std::span<double> state) const {
  state[0] = theta_;
  state[1] = theta_dot_;
}

void Pendulum::load_state(std::span<const double> state) {
  theta_ = state[0];
  theta_dot_ = state[1];
}

void Pendulum::write_observation(std::span<float> obs) const {
  obs[0] = static_cast<float>(std::cos(theta_));
  obs[1] = static_cast<float>(std::sin(theta_));
  obs[2] = static_cast<float>(theta_dot_);
}

}  // namespace rlrun
