#include "rlrun/envs/car_racing/line_follower.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "rlrun/core/errors.hpp"
#include "rlrun/envs/car_racing/car_racing.hpp"

namespace rlrun {

namespace {

constexpr int kLookahead = 6;       // track points ahead of the nearest one (3.5 m each)
constexpr int kBendHorizon = 14;    // points whose heading change sets the speed
constexpr double kFastSpeed = 110;  // m/s on straights
constexpr double kSlowSpeed = 45;   // m/s through the sharpest bends
constexpr double kSteerGain = 2.5;  // steer action per radian of heading error

double wrap_angle(double a) { return std::remainder(a, 2 * std::numbers::pi); }

size_t nearest_point(const std::array<double, 2>& p, std::span<const TrackPoint> track) {
  size_t best = 0;
  double best_d = INFINITY;
  for (size_t i = 0; i < track.size(); ++i) {
    const double d = std::hypot(track[i].x - p[0], track[i].y - p[1]);
    if (d < best_d) best_d = d, best = i;
  }
  return best;
}

}  // namespace

std::array<float, 3> line_follower_controls(const CarState& car,
                                            std::span<const TrackPoint> track) {
  const size_t n = track.size();
  const auto& hull = car.hull;
  const size_t near = nearest_point(hull.position, track);
  const TrackPoint& target = track[(near + kLookahead) % n];
  // The car's forward axis is its local +y: (-sin angle, cos angle).
  const double heading = hull.angle + std::numbers::pi / 2;
  const double to_target = std::atan2(target.y - hull.position[1], target.x - hull.position[0]);
  const double error = wrap_angle(to_target - heading);  // > 0: target on the left
  // steer(-action[0]): a left turn (positive joint angle) is a negative action.
  const float steer = static_cast<float>(std::clamp(-kSteerGain * error, -1.0, 1.0));

  double bend = 0;  // the largest heading change over the next points
  for (int k = 1; k <= kBendHorizon; ++k)
    bend = std::max(bend, std::abs(wrap_angle(track[(near + k) % n].beta - track[near].beta)));
  const double target_speed =
      kSlowSpeed + (kFastSpeed - kSlowSpeed) * std::max(0.0, 1 - bend / 1.2);
  const double speed = std::hypot(hull.linear_velocity[0], hull.linear_velocity[1]);
  const float gas = speed < target_speed && std::abs(steer) < 0.5f ? 1.0f : 0.0f;
  const float brake = speed > target_speed + 4 ? 0.6f : 0.0f;
  return {steer, gas, brake};
}

std::function<void(const Eigen::MatrixXf&, Eigen::MatrixXf&)> line_follower_actions(Env& env) {
  auto* racing = dynamic_cast<CarRacing*>(&env.unwrapped());
  if (!racing)
    throw UsageError("the line-follower policy is CarRacing-v3's; this env is " +
                     env.unwrapped().id());
  return [racing](const Eigen::MatrixXf& obs, Eigen::MatrixXf& action) {
    if (obs.cols() != 1)
      throw UsageError("the line-follower policy drives one CarRacing-v3 env at a time");
    const std::array<float, 3> c = line_follower_controls(racing->car(), racing->track());
    if (racing->config().continuous) {
      action.resize(3, 1);
      for (int i = 0; i < 3; ++i) action(i, 0) = c[i];
      return;
    }
    // Discrete(5): Gymnasium's action 1 steers with steer(-0.6) (a right turn, as
    // action[0] = +0.6 would), action 2 with steer(+0.6).
    action.resize(1, 1);
    int a = 0;
    if (c[2] > 0)
      a = 4;
    else if (std::abs(c[0]) > 0.2f)
      a = c[0] > 0 ? 1 : 2;
    else if (c[1] > 0)
      a = 3;
    action(0, 0) = static_cast<float>(a);
  };
}

}  // namespace rlrun
