// Acrobot-v1's picture: gymnasium/envs/classic_control/acrobot.py render(), same geometry and
// colours (500x500 scene, y up): the goal line one link length above the pivot, two cyan
// links, yellow joints at the pivot and the elbow.
#include <cmath>
#include <numbers>

#include "rlrun/envs/classic/classic_render.hpp"
#include "rlrun/frame.hpp"

namespace rlrun {

void draw_acrobot(std::span<const double> state, double /*last_action*/, Frame& frame) {
  constexpr double kDim = 500;
  constexpr double kLink1 = 1.0, kLink2 = 1.0;
  constexpr double kBound = kLink1 + kLink2 + 0.2;  // 2.2
  constexpr double kScale = kDim / (kBound * 2);
  constexpr double kOffset = kDim / 2;
  const double th1 = state[0], th2 = state[1];
  frame.begin_scene(kDim, kDim, {255, 255, 255});

  // Joint positions in acrobot.py's frame, then [:, ::-1] swaps to (x, y) screen order.
  const double p1_0 = -kLink1 * std::cos(th1) * kScale, p1_1 = kLink1 * std::sin(th1) * kScale;
  const Point joints[] = {{0, 0}, {p1_1, p1_0}};
  const double thetas[] = {th1 - std::numbers::pi / 2, th1 + th2 - std::numbers::pi / 2};
  const double lengths[] = {kLink1 * kScale, kLink2 * kScale};

  // pygame.draw.line: the height the tip must pass, 1 unit above the pivot; pygame draws it
  // on pixel row int(y), hence the snap to that row's centre.
  const double line_y = std::trunc(1 * kScale + kOffset) + 0.5;
  frame.line({-2.2 * kScale + kOffset, line_y}, {2.2 * kScale + kOffset, line_y}, {0, 0, 0}, 1.0);

  for (int i = 0; i < 2; ++i) {
    const Point at{joints[i].x + kOffset, joints[i].y + kOffset};
    const double l = 0, r = lengths[i], t = 0.1 * kScale, b = -0.1 * kScale;
    const Point link[] = {rotate({l, b}, thetas[i]) + at, rotate({l, t}, thetas[i]) + at,
                          rotate({r, t}, thetas[i]) + at, rotate({r, b}, thetas[i]) + at};
    frame.polygon(link, {0, 204, 204});
    frame.circle({std::trunc(at.x), std::trunc(at.y)}, static_cast<int>(0.1 * kScale),
                 {204, 204, 0});
  }
  frame.end_scene();
}

void acrobot_state_from_observation(std::span<const float> obs, std::span<double> state) {
  // [cos th1, sin th1, cos th2, sin th2, dth1, dth2]
  state[0] = std::atan2(static_cast<double>(obs[1]), static_cast<double>(obs[0]));
  state[1] = std::atan2(static_cast<double>(obs[3]), static_cast<double>(obs[2]));
  state[2] = obs[4];
  state[3] = obs[5];
}

}  // namespace rlrun
