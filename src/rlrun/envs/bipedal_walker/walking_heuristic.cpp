#include "rlrun/envs/bipedal_walker/walking_heuristic.hpp"

#include <algorithm>
#include <cmath>
#include <memory>
#include <stdexcept>
#include <string>

#include "rlrun/core/errors.hpp"
#include "rlrun/envs/bipedal_walker/bipedal_walker.hpp"

namespace rlrun {

void WalkingHeuristic::restart() { *this = WalkingHeuristic{}; }

std::array<float, 4> WalkingHeuristic::act(std::span<const float> s) {
  if (s.size() != 24)
    throw std::invalid_argument("the walking heuristic reads 24 observation values, got " +
                                std::to_string(s.size()));
  const size_t moving_base = 4 + 5 * static_cast<size_t>(moving_leg_);
  const size_t supporting_base = 4 + 5 * static_cast<size_t>(supporting_leg_);
  // Targets (hip -0.8 .. +1.1, knee -0.6 .. +0.9); NaN = none. Gymnasium tests them with
  // `if hip_targ[0]:`, so a target of exactly 0.0 counts as none too.
  double hip_targ[2] = {NAN, NAN}, knee_targ[2] = {NAN, NAN};
  double hip_todo[2] = {0.0, 0.0}, knee_todo[2] = {0.0, 0.0};
  const size_t moving = static_cast<size_t>(moving_leg_), supporting = 1 - moving;

  if (state_ == kStayOnOneLeg) {
    hip_targ[moving] = 1.1;
    knee_targ[moving] = -0.6;
    supporting_knee_angle_ += 0.03;
    if (s[2] > kSpeed) supporting_knee_angle_ += 0.03;
    supporting_knee_angle_ = std::min(supporting_knee_angle_, kSupportKneeAngle);
    knee_targ[supporting] = supporting_knee_angle_;
    if (s[supporting_base + 0] < 0.10) state_ = kPutOtherDown;  // supporting leg is behind
  }
  if (state_ == kPutOtherDown) {
    hip_targ[moving] = +0.1;
    knee_targ[moving] = kSupportKneeAngle;
    knee_targ[supporting] = supporting_knee_angle_;
    if (s[moving_base + 4] != 0.0f) {
      state_ = kPushOff;
      supporting_knee_angle_ = std::min<double>(s[moving_base + 2], kSupportKneeAngle);
    }
  }
  if (state_ == kPushOff) {
    knee_targ[moving] = supporting_knee_angle_;
    knee_targ[supporting] = +1.0;
    if (s[supporting_base + 2] > 0.88 || s[2] > 1.2 * kSpeed) {
      state_ = kStayOnOneLeg;
      moving_leg_ = 1 - moving_leg_;
      supporting_leg_ = 1 - moving_leg_;
    }
  }

  auto set = [](double target) { return !std::isnan(target) && target != 0.0; };
  if (set(hip_targ[0])) hip_todo[0] = 0.9 * (hip_targ[0] - s[4]) - 0.25 * s[5];
  if (set(hip_targ[1])) hip_todo[1] = 0.9 * (hip_targ[1] - s[9]) - 0.25 * s[10];
  if (set(knee_targ[0])) knee_todo[0] = 4.0 * (knee_targ[0] - s[6]) - 0.25 * s[7];
  if (set(knee_targ[1])) knee_todo[1] = 4.0 * (knee_targ[1] - s[11]) - 0.25 * s[12];

  for (double& h : hip_todo) h -= 0.9 * (0 - s[0]) - 1.5 * s[1];  // PID to keep head straight
  for (double& k : knee_todo) k -= 15.0 * s[3];  // vertical speed, to damp oscillations

  const double raw[4] = {hip_todo[0], knee_todo[0], hip_todo[1], knee_todo[1]};
  std::array<float, 4> a{};
  for (size_t i = 0; i < 4; ++i) a[i] = static_cast<float>(std::clamp(0.5 * raw[i], -1.0, 1.0));
  return a;
}

PolicyFn walking_heuristic_actions(Env& env) {
  const auto* walker = dynamic_cast<const BipedalWalker*>(&env.unwrapped());
  if (!walker)
    throw UsageError(
        "the heuristic policy is BipedalWalker's (BipedalWalker-v3, "
        "BipedalWalkerHardcore-v3); this env is " +
        env.unwrapped().id());
  auto heuristic = std::make_shared<WalkingHeuristic>();
  return [walker, heuristic](const Eigen::MatrixXf& obs, Eigen::MatrixXf& action) {
    action.resize(4, 1);
    if (walker->episode_steps() == 0) {
      // Gymnasium's __main__ loop steps with a = 0 first and hands the heuristic the
      // observations of the steps after it (never the reset's): the same here.
      heuristic->restart();
      action.setZero();
      return;
    }
    const auto a =
        heuristic->act(std::span<const float>(obs.data(), static_cast<size_t>(obs.rows())));
    for (int i = 0; i < 4; ++i) action(i, 0) = a[static_cast<size_t>(i)];
  };
}

}  // namespace rlrun
