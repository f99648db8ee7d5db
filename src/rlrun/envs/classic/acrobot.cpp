#include "rlrun/envs/classic/acrobot.hpp"

#include "rlrun/envs/classic/classic_render.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

namespace rlrun {

namespace {

using State5 = std::array<double, 5>;  // state plus the torque (acrobot.py's s_augmented)

constexpr double kPi = std::numbers::pi;
constexpr double kDt = 0.2;
constexpr double kLinkLength1 = 1.0;
constexpr double kLinkMass1 = 1.0;
constexpr double kLinkMass2 = 1.0;
constexpr double kLinkComPos1 = 0.5;
constexpr double kLinkComPos2 = 0.5;
constexpr double kLinkMoi = 1.0;
constexpr double kMaxVel1 = 4 * kPi;
constexpr double kMaxVel2 = 9 * kPi;
constexpr std::array<double, 3> kAvailTorque = {-1.0, 0.0, 1.0};
constexpr double kResetBound = 0.1;

// acrobot.py _dsdt with book_or_nips == "book".
State5 dsdt(const State5& s) {
  constexpr double m1 = kLinkMass1, m2 = kLinkMass2, l1 = kLinkLength1;
  constexpr double lc1 = kLinkComPos1, lc2 = kLinkComPos2, I1 = kLinkMoi, I2 = kLinkMoi;
  constexpr double g = 9.8;
  const double a = s[4];
  const double theta1 = s[0], theta2 = s[1], dtheta1 = s[2], dtheta2 = s[3];
  const double d1 =
      m1 * (lc1 * lc1) + m2 * ((l1 * l1) + (lc2 * lc2) + 2 * l1 * lc2 * std::cos(theta2)) + I1 + I2;
  const double d2 = m2 * ((lc2 * lc2) + l1 * lc2 * std::cos(theta2)) + I2;
  const double phi2 = m2 * lc2 * g * std::cos(theta1 + theta2 - kPi / 2.0);
  const double phi1 = -m2 * l1 * lc2 * (dtheta2 * dtheta2) * std::sin(theta2) -
                      2 * m2 * l1 * lc2 * dtheta2 * dtheta1 * std::sin(theta2) +
                      (m1 * lc1 + m2 * l1) * g * std::cos(theta1 - kPi / 2) + phi2;
  const double ddtheta2 =
      (a + d2 / d1 * phi1 - m2 * l1 * lc2 * (dtheta1 * dtheta1) * std::sin(theta2) - phi2) /
      (m2 * (lc2 * lc2) + I2 - (d2 * d2) / d1);
  const double ddtheta1 = -(d2 * ddtheta2 + phi1) / d1;
  return {dtheta1, dtheta2, ddtheta1, ddtheta2, 0.0};
}

// acrobot.py rk4 over t = [0, dt]: a single classic Runge-Kutta step.
State5 rk4_step(const State5& y0, double dt) {
  const double dt2 = dt / 2.0;
  auto shifted = [&y0](const State5& k, double h) {
    State5 y;
    for (size_t i = 0; i < y.size(); ++i) y[i] = y0[i] + h * k[i];
    return y;
  };
  const State5 k1 = dsdt(y0);
  const State5 k2 = dsdt(shifted(k1, dt2));
  const State5 k3 = dsdt(shifted(k2, dt2));
  const State5 k4 = dsdt(shifted(k3, dt));
  State5 y;
  for (size_t i = 0; i < y.size(); ++i)
    y[i] = y0[i] + dt / 6.0 * (k1[i] + 2 * k2[i] + 2 * k3[i] + k4[i]);
  return y;
}

// acrobot.py wrap: shifts x by whole periods into [m, M] (unlike bound, which clips).
double wrap(double x, double m, double big_m) {
  const double diff = big_m - m;
  while (x > big_m) x = x - diff;
  while (x < m) x = x + diff;
  return x;
}

// acrobot.py bound: min(max(x, m), M).
double bound(double x, double m, double big_m) { return std::min(std::max(x, m), big_m); }

// np_random.uniform(-0.1, 0.1, size=(4,)).astype(np.float32): the start state is float32.
bool initial_state(NumpyRandom& np_random, std::span<double> state) {
  for (double& s : state) s = static_cast<float>(np_random.uniform(-kResetBound, kResetBound));
  return true;
}

void observation(std::span<const double> state, std::span<float> obs) {
  obs[0] = static_cast<float>(std::cos(state[0]));
  obs[1] = static_cast<float>(std::sin(state[0]));
  obs[2] = static_cast<float>(std::cos(state[1]));
  obs[3] = static_cast<float>(std::sin(state[1]));
  obs[4] = static_cast<float>(state[2]);
  obs[5] = static_cast<float>(state[3]);
}

}  // namespace

// acrobot.py: SCREEN_DIM 500, render_fps 15; the picture is in acrobot_render.cpp.
const ClassicSpec kAcrobot{"Acrobot-v1",
                           {500, 500, 15},
                           4,
                           true,
                           initial_state,
                           observation,
                           draw_acrobot,
                           acrobot_state_from_observation};

Acrobot::Acrobot(const Config&)
    : ClassicControlEnv(kAcrobot,
                        Space::box({-1.0f, -1.0f, -1.0f, -1.0f, static_cast<float>(-kMaxVel1),
                                    static_cast<float>(-kMaxVel2)},
                                   {1.0f, 1.0f, 1.0f, 1.0f, static_cast<float>(kMaxVel1),
                                    static_cast<float>(kMaxVel2)}),
                        Space::discrete(3)) {}

StepResult Acrobot::step(std::span<const float> action, std::span<float> obs) {
  require_reset();
  const int a = discrete_action(action);
  info_.clear();
  // torque_noise_max is 0 in Gymnasium, so no noise is drawn.
  const State5 augmented = {state_[0], state_[1], state_[2], state_[3], kAvailTorque[a]};
  const State5 ns = rk4_step(augmented, kDt);
  state_[0] = wrap(ns[0], -kPi, kPi);
  state_[1] = wrap(ns[1], -kPi, kPi);
  state_[2] = bound(ns[2], -kMaxVel1, kMaxVel1);
  state_[3] = bound(ns[3], -kMaxVel2, kMaxVel2);
  state_is_float32_ = false;

  // _terminal: the free end is more than one link length above the pivot.
  const bool terminated = -std::cos(state_[0]) - std::cos(state_[1] + state_[0]) > 1.0;
  write_observation(obs);
  return {terminated ? 0.0 : -1.0, terminated, false};
}

}  // namespace rlrun
