#include "rlrun/envs/classic/cartpole.hpp"

#include "rlrun/envs/classic/classic_render.hpp"

#include <cmath>
#include <limits>
#include <numbers>

namespace rlrun {

namespace {

constexpr double kGravity = 9.8;
constexpr double kMassCart = 1.0;
constexpr double kMassPole = 0.1;
constexpr double kTotalMass = kMassPole + kMassCart;
constexpr double kLength = 0.5;  // half the pole's length
constexpr double kPoleMassLength = kMassPole * kLength;
constexpr double kForceMag = 10.0;
constexpr double kTau = 0.02;  // seconds between state updates
// Gymnasium writes 12 * 2 * math.pi / 360; the same expression keeps the same rounding.
constexpr double kThetaThresholdRadians = 12 * 2 * std::numbers::pi / 360;
constexpr double kXThreshold = 2.4;
constexpr double kResetBound = 0.05;

Space make_observation_space() {
  // The angle bound is twice the failure angle so that a failing observation is still inside.
  constexpr float kInf = std::numeric_limits<float>::infinity();
  const float x = static_cast<float>(kXThreshold * 2);
  const float theta = static_cast<float>(kThetaThresholdRadians * 2);
  return Space::box({-x, -kInf, -theta, -kInf}, {x, kInf, theta, kInf});
}

// np_random.uniform(low=-0.05, high=0.05, size=(4,))
bool initial_state(NumpyRandom& np_random, std::span<double> state) {
  for (double& s : state) s = np_random.uniform(-kResetBound, kResetBound);
  return false;
}

// The observation is the state, in float32.
void observation(std::span<const double> state, std::span<float> obs) {
  for (size_t i = 0; i < 4; ++i) obs[i] = static_cast<float>(state[i]);
}

}  // namespace

// cartpole.py: screen 600x400, render_fps 50; the picture is in cartpole_render.cpp.
const ClassicSpec kCartPole{"CartPole-v1",
                            {600, 400, 50},
                            4,
                            false,
                            initial_state,
                            observation,
                            draw_cartpole,
                            cartpole_state_from_observation};

CartPole::CartPole(const Config& config)
    : ClassicControlEnv(kCartPole, make_observation_space(), Space::discrete(2)), config_(config) {}

StepResult CartPole::step(std::span<const float> action, std::span<float> obs) {
  require_reset();
  const int a = discrete_action(action);
  info_.clear();
  auto& [x, x_dot, theta, theta_dot] = state_;
  const double force = a == 1 ? kForceMag : -kForceMag;
  const double costheta = std::cos(theta);
  const double sintheta = std::sin(theta);

  // Equations of https://coneural.org/florian/papers/05_cart_pole.pdf, evaluated in the same
  // order as cartpole.py so results agree to the last bit where libm does.
  const double temp = (force + kPoleMassLength * (theta_dot * theta_dot) * sintheta) / kTotalMass;
  const double thetaacc = (kGravity * sintheta - costheta * temp) /
                          (kLength * (4.0 / 3.0 - kMassPole * (costheta * costheta) / kTotalMass));
  const double xacc = temp - kPoleMassLength * thetaacc * costheta / kTotalMass;

  // kinematics_integrator == "euler" (the default; Gymnasium never changes it).
  x = x + kTau * x_dot;
  x_dot = x_dot + kTau * xacc;
  theta = theta + kTau * theta_dot;
  theta_dot = theta_dot + kTau * thetaacc;

  const bool terminated = x < -kXThreshold || x > kXThreshold || theta < -kThetaThresholdRadians ||
                          theta > kThetaThresholdRadians;

  double reward;
  if (!terminated) {
    reward = config_.sutton_barto_reward ? 0.0 : 1.0;
  } else if (steps_beyond_terminated_ < 0) {
    // The pole just fell: the terminating step still earns the usual reward.
    steps_beyond_terminated_ = 0;
    reward = config_.sutton_barto_reward ? -1.0 : 1.0;
  } else {
    // Stepping past termination is undefined behaviour in Gymnasium; it pays 0 (or -1).
    ++steps_beyond_terminated_;
    reward = config_.sutton_barto_reward ? -1.0 : 0.0;
  }

  write_observation(obs);
  return {reward, terminated, false};
}

}  // namespace rlrun
