#pragma once
// A vehicle in the traffic envs' pictures (TrafficSignal-v0, TrafficNetwork-v0): a 5 m x 1.8 m
// box at SUMO's position (the front bumper's centre) and heading (degrees clockwise from
// north), blue when moving and red when waiting (below 0.1 m/s, SUMO's waiting threshold).
#include <cmath>

#include "rlrun/frame.hpp"

namespace rlrun {

// `at(x, y)` maps SUMO's metres to the scene's coordinates.
template <class At>
void draw_vehicle(Frame& frame, const At& at, double x, double y, double angle_degrees,
                  double speed) {
  constexpr double kLength = 5.0, kHalfWidth = 0.9;
  const double heading = angle_degrees * M_PI / 180.0;
  const double fx = std::sin(heading), fy = std::cos(heading);  // forward
  const double sx = fy, sy = -fx;                               // to the right
  const Point box[] = {at(x + sx * kHalfWidth, y + sy * kHalfWidth),
                       at(x - sx * kHalfWidth, y - sy * kHalfWidth),
                       at(x - sx * kHalfWidth - fx * kLength, y - sy * kHalfWidth - fy * kLength),
                       at(x + sx * kHalfWidth - fx * kLength, y + sy * kHalfWidth - fy * kLength)};
  frame.polygon(box, speed < 0.1 ? Rgb{210, 40, 40} : Rgb{60, 110, 220});
}

}  // namespace rlrun
