// Pendulum-v1's picture: gymnasium/envs/classic_control/pendulum.py render(), same geometry
// and colours (500x500 scene, y up). Gymnasium blits assets/clockwise.png, scaled with the
// last torque, for the action; here that arrow is drawn as a 3/4-circle arc with a head,
// same size (scale * |u| / 2) and the same sense (clockwise for u <= 0, mirrored for u > 0).
#include <cmath>
#include <numbers>

#include "rlrun/envs/classic/classic_render.hpp"
#include "rlrun/frame.hpp"

namespace rlrun {

namespace {

constexpr double kDim = 500;
constexpr double kBound = 2.2;
constexpr double kScale = kDim / (kBound * 2);
constexpr double kOffset = 250;  // screen_dim // 2
constexpr Rgb kRodColor{204, 77, 77};

// Torque arrow of side `size` around the axle; counter-clockwise when ccw.
void draw_torque_arrow(Frame& frame, double size, bool ccw) {
  cairo_t* cr = frame.cairo();
  constexpr double kPi = std::numbers::pi;
  const double radius = size * 0.38;
  const double width = size * 0.09;
  // The arc spans 270 degrees with its gap below the axle; the head sits at the arc's end.
  const double start = ccw ? -kPi / 4 : 5 * kPi / 4;
  const double end = ccw ? 5 * kPi / 4 : -kPi / 4;
  cairo_new_path(cr);
  if (ccw)
    cairo_arc(cr, kOffset, kOffset, radius, start, end - 0.25);
  else
    cairo_arc_negative(cr, kOffset, kOffset, radius, start, end + 0.25);
  cairo_set_source_rgb(cr, 0, 0, 0);
  cairo_set_line_width(cr, width);
  cairo_stroke(cr);
  // Head: a triangle at angle `end`, pointing along the direction of travel.
  const Point tip{kOffset + radius * std::cos(end), kOffset + radius * std::sin(end)};
  const double travel = ccw ? end + kPi / 2 : end - kPi / 2;  // tangent direction
  const Point dir{std::cos(travel), std::sin(travel)};
  const Point normal{-dir.y, dir.x};
  const double head = width * 2.6;
  const Point head_points[] = {{tip.x + dir.x * head * 0.5, tip.y + dir.y * head * 0.5},
                               {tip.x - dir.x * head * 0.5 + normal.x * head * 0.6,
                                tip.y - dir.y * head * 0.5 + normal.y * head * 0.6},
                               {tip.x - dir.x * head * 0.5 - normal.x * head * 0.6,
                                tip.y - dir.y * head * 0.5 - normal.y * head * 0.6}};
  frame.polygon(head_points, {0, 0, 0});
}

}  // namespace

void draw_pendulum(std::span<const double> state, double last_action, Frame& frame) {
  const double theta = state[0];
  frame.begin_scene(kDim, kDim, {255, 255, 255});
  const double rod_length = 1 * kScale;
  const double rod_width = 0.2 * kScale;
  const double l = 0, r = rod_length, t = rod_width / 2, b = -rod_width / 2;
  // theta = 0 is upright: the rod (drawn along +x) turns by theta + pi/2.
  const double angle = theta + std::numbers::pi / 2;
  const Point centre{kOffset, kOffset};
  const Point rod[] = {rotate({l, b}, angle) + centre, rotate({l, t}, angle) + centre,
                       rotate({r, t}, angle) + centre, rotate({r, b}, angle) + centre};
  frame.polygon(rod, kRodColor);
  const double end_radius = static_cast<int>(rod_width / 2);  // gfxdraw takes int radii
  frame.circle(centre, end_radius, kRodColor);
  const Point end = rotate({rod_length, 0}, angle) + centre;
  frame.circle({std::trunc(end.x), std::trunc(end.y)}, end_radius, kRodColor);
  // The action of the last step (pendulum.py draws none before the first step).
  if (!std::isnan(last_action) && last_action != 0.0)
    draw_torque_arrow(frame, kScale * std::abs(last_action) / 2, last_action > 0);
  // The axle: int(0.05 * scale) = 5.
  frame.circle(centre, static_cast<int>(0.05 * kScale), {0, 0, 0});
  frame.end_scene();
}

void pendulum_state_from_observation(std::span<const float> obs, std::span<double> state) {
  state[0] = std::atan2(static_cast<double>(obs[1]), static_cast<double>(obs[0]));
  state[1] = obs[2];
}

}  // namespace rlrun
