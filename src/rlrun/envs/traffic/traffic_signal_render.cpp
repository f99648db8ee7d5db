// TrafficSignal-v0's picture: the intersection from above, as sumo-gui shows it in its
// "standard" scheme, simplified — grey lanes, a stop line coloured by the light of its
// approach (green or red: a yellow begins and ends within one step), and each vehicle as a
// 5 m x 1.8 m box at its SUMO position and heading, blue when moving and red when waiting
// (speed < 0.1 m/s, SUMO's waiting threshold).
#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "rlrun/envs/traffic/traffic_signal.hpp"
#include "rlrun/envs/traffic/vehicle_picture.hpp"
#include "rlrun/frame.hpp"

namespace rlrun {

bool TrafficSignal::render(Frame& frame) const {
  if (!has_state_) throw std::logic_error("TrafficSignal-v0: call reset() before render()");
  // The scene: every lane's bounding box, plus a margin.
  double min_x = 1e300, min_y = 1e300, max_x = -1e300, max_y = -1e300;
  for (const auto* lanes : {&incoming_, &outgoing_})
    for (const Lane& lane : *lanes)
      for (const auto& p : lane.shape) {
        min_x = std::min(min_x, p[0]);
        max_x = std::max(max_x, p[0]);
        min_y = std::min(min_y, p[1]);
        max_y = std::max(max_y, p[1]);
      }
  constexpr double kMargin = 8.0;
  min_x -= kMargin, min_y -= kMargin, max_x += kMargin, max_y += kMargin;
  const double size = std::max(max_x - min_x, max_y - min_y);
  const auto at = [&](double x, double y) { return Point{x - min_x, y - min_y}; };
  frame.begin_scene(size, size, {96, 140, 80});  // grass

  // The junction's area, then the lanes (light grey) and their stop lines.
  for (const auto* lanes : {&incoming_, &outgoing_})
    for (const Lane& lane : *lanes)
      for (size_t i = 1; i < lane.shape.size(); ++i)
        frame.line(at(lane.shape[i - 1][0], lane.shape[i - 1][1]),
                   at(lane.shape[i][0], lane.shape[i][1]), {70, 70, 70}, lane.width);
  for (const Lane& in : incoming_)
    for (const Lane& out : outgoing_)  // the crossing area between stop lines
      frame.line(at(in.shape.back()[0], in.shape.back()[1]),
                 at(out.shape.front()[0], out.shape.front()[1]), {70, 70, 70}, in.width);
  for (const Lane& lane : incoming_) {
    const auto& end = lane.shape.back();
    const auto& before = lane.shape[lane.shape.size() - 2];
    const double dx = end[0] - before[0], dy = end[1] - before[1];
    const double length = std::hypot(dx, dy);
    const double nx = -dy / length * lane.width / 2, ny = dx / length * lane.width / 2;
    Rgb light{220, 30, 30};
    if (lane.approach == green_) light = Rgb{30, 200, 60};  // yellow ends within a step
    frame.line(at(end[0] - nx, end[1] - ny), at(end[0] + nx, end[1] + ny), light, 3.0);
  }

  // Vehicles (vehicle_picture.hpp).
  // The vehicles come with a subscription made on the first render: unwatched training does
  // not pay for them (a third of the speed).
  if (!vehicles_subscribed_ && !finished_) {
    try {
      sumo_->subscribe_vehicles(state_);
    } catch (const std::exception& e) {
      sumo_failed(e);
    }
    vehicles_subscribed_ = true;
  }
  for (const SumoVehicle& vehicle : state_.vehicles)
    draw_vehicle(frame, at, vehicle.x, vehicle.y, vehicle.angle, vehicle.speed);
  frame.end_scene();
  return true;
}

}  // namespace rlrun
