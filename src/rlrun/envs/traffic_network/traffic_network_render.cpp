// The traffic envs' picture (TrafficSignal-v0's too: its one junction is the whole map): the
// network from above (all of it, or `render_radius` metres around `render_focus`), as sumo-gui
// shows it in its "standard" scheme, simplified — grass, grey lanes, each agent's stop lines
// green or red by its current green (a yellow begins and ends within one decision), the
// vehicles (vehicle_picture.hpp).
#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "rlrun/core/errors.hpp"
#include "rlrun/envs/traffic_network/traffic_network.hpp"
#include "rlrun/envs/traffic_network/vehicle_picture.hpp"
#include "rlrun/frame.hpp"

namespace rlrun {

using namespace traffic;

bool TrafficNetwork::render(Frame& frame) const {
  if (!has_state_) throw std::logic_error(name_ + ": call reset() before render()");
  // Plain variables, not a structured binding: the lambdas below capture them, which clang
  // before 16 (scripts/fuzz.sh's clang 14) refuses for bindings.
  double x0 = geometry_.bounds[0], y0 = geometry_.bounds[1];
  double x1 = geometry_.bounds[2], y1 = geometry_.bounds[3];
  if (!config_.render_focus.empty()) {
    const auto at = geometry_.junctions.find(config_.render_focus);
    if (at == geometry_.junctions.end())
      throw UsageError("render_focus: '" + config_.render_focus + "' is not a junction of " +
                       scenario_.files.net);
    x0 = at->second[0] - config_.render_radius, x1 = at->second[0] + config_.render_radius;
    y0 = at->second[1] - config_.render_radius, y1 = at->second[1] + config_.render_radius;
  }
  constexpr double kMargin = 8.0;
  x0 -= kMargin, y0 -= kMargin, x1 += kMargin, y1 += kMargin;
  const double size = std::max(x1 - x0, y1 - y0);
  const auto at = [&](double x, double y) { return Point{x - x0, y - y0}; };
  const auto visible = [&](double x, double y) { return x >= x0 && x <= x1 && y >= y0 && y <= y1; };
  frame.begin_scene(size, size, {96, 140, 80});  // grass

  for (const LaneGeometry& lane : geometry_.lanes)
    for (size_t i = 1; i < lane.shape.size(); ++i)
      frame.line(at(lane.shape[i - 1][0], lane.shape[i - 1][1]),
                 at(lane.shape[i][0], lane.shape[i][1]), {70, 70, 70}, lane.width);
  // Stop lines: an incoming lane is green when any of its links is green in the agent's
  // current green (a yellow begins and ends within one decision).
  for (const LightAgent& agent : agents_) {
    const std::string& state = agent.green_state();
    for (size_t k = 0; k < agent.in_slots().size(); ++k) {
      const LaneGeometry& lane = geometry_.lane(lanes_[agent.in_slots()[k]]);
      if (lane.shape.size() < 2) continue;
      bool green = false;
      for (const SignalLink& link : agent.links())
        if (link.from == lane.id && static_cast<size_t>(link.index) < state.size())
          green = green || state[link.index] == 'G' || state[link.index] == 'g';
      const auto& end = lane.shape.back();
      const auto& before = lane.shape[lane.shape.size() - 2];
      const double dx = end[0] - before[0], dy = end[1] - before[1];
      const double length = std::max(std::hypot(dx, dy), 1e-9);
      const double nx = -dy / length * lane.width / 2, ny = dx / length * lane.width / 2;
      frame.line(at(end[0] - nx, end[1] - ny), at(end[0] + nx, end[1] + ny),
                 green ? Rgb{30, 200, 60} : Rgb{220, 30, 30}, 2.0);
    }
  }

  // The vehicles come with a subscription made on the first render when training did not need
  // them: unwatched training with the queue or pressure reward does not pay for them.
  if (!vehicles_subscribed_ && !finished_) {
    try {
      sumo_->subscribe_vehicles(geometry_.junctions.begin()->first, reading_);
    } catch (const std::exception& e) {
      sumo_failed(e);
    }
    vehicles_subscribed_ = true;
  }
  for (const VehicleReading& vehicle : reading_.vehicles)
    if (visible(vehicle.x, vehicle.y))
      draw_vehicle(frame, at, vehicle.x, vehicle.y, vehicle.angle, vehicle.speed);
  frame.end_scene();
  return true;
}

}  // namespace rlrun
