// The picture of MountainCar-v0 and MountainCarContinuous-v0: gymnasium/envs/classic_control/
// mountain_car.py and continuous_mountain_car.py render(), identical but for the goal
// position: the hill curve, the car with two wheels, the flag.
#include "rlrun/envs/classic/classic_render.hpp"

#include <array>
#include <cmath>

namespace rlrun {

namespace {

constexpr double kMinPosition = -1.2, kMaxPosition = 0.6;

// mountain_car.py _height: the hill profile.
double height(double x) { return std::sin(3 * x) * 0.45 + 0.55; }

void draw_scene(Frame& frame, double position, double goal_position) {
  constexpr double kWidth = 600, kHeight = 400;
  constexpr double kScale = kWidth / (kMaxPosition - kMinPosition);
  constexpr double kCarWidth = 40, kCarHeight = 20;
  constexpr double kClearance = 10;
  frame.begin_scene(kWidth, kHeight, {255, 255, 255});

  // pygame.draw.aalines through 100 samples of the hill (np.linspace).
  std::array<Point, 100> hill;
  for (size_t i = 0; i < hill.size(); ++i) {
    const double x = kMinPosition + (kMaxPosition - kMinPosition) * i / (hill.size() - 1);
    hill[i] = {(x - kMinPosition) * kScale, height(x) * kScale};
  }
  frame.polyline(hill, {0, 0, 0}, 1.0);

  // The car, tilted with the slope angle's stand-in cos(3 * pos) as in Gymnasium.
  const double tilt = std::cos(3 * position);
  const Point base{(position - kMinPosition) * kScale, kClearance + height(position) * kScale};
  const double l = -kCarWidth / 2, r = kCarWidth / 2, t = kCarHeight, b = 0;
  const Point car[] = {rotate({l, b}, tilt) + base, rotate({l, t}, tilt) + base,
                       rotate({r, t}, tilt) + base, rotate({r, b}, tilt) + base};
  frame.polygon(car, {0, 0, 0});
  for (const Point wheel_offset : {Point{kCarWidth / 4, 0}, Point{-kCarWidth / 4, 0}}) {
    const Point wheel = rotate(wheel_offset, tilt) + base;
    frame.circle({std::trunc(wheel.x), std::trunc(wheel.y)}, static_cast<int>(kCarHeight / 2.5),
                 {128, 128, 128});
  }

  // The flag: a 50 px pole (gfxdraw.vline) and a yellow pennant.
  const double flag_x = static_cast<int>((goal_position - kMinPosition) * kScale);
  const double flag_y1 = static_cast<int>(height(goal_position) * kScale);
  const double flag_y2 = flag_y1 + 50;
  frame.line({flag_x + 0.5, flag_y1}, {flag_x + 0.5, flag_y2 + 1}, {0, 0, 0}, 1.0);
  const Point pennant[] = {{flag_x, flag_y2}, {flag_x, flag_y2 - 10}, {flag_x + 25, flag_y2 - 5}};
  frame.polygon(pennant, {204, 204, 0});
  frame.end_scene();
}

}  // namespace

void draw_mountain_car(std::span<const double> state, double /*last_action*/, Frame& frame) {
  draw_scene(frame, state[0], /*goal_position=*/0.5);
}

void draw_mountain_car_continuous(std::span<const double> state, double /*last_action*/,
                                  Frame& frame) {
  draw_scene(frame, state[0], /*goal_position=*/0.45);
}

void mountain_car_state_from_observation(std::span<const float> obs, std::span<double> state) {
  state[0] = obs[0];  // the observation is the state
  state[1] = obs[1];
}

}  // namespace rlrun
