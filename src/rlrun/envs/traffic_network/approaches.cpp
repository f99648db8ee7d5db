#include "rlrun/envs/traffic_network/approaches.hpp"

#include <algorithm>
#include <cmath>

namespace rlrun::traffic {

namespace {

constexpr double kVehicleSpace = 5.0 + 2.5;  // length + minGap of the scenario's cars (sumo-rl)

// N, S, E or W: where an incoming lane starts, seen from the junction.
int approach_of(const LaneGeometry& lane, const std::array<double, 2>& centre) {
  const double dx = lane.shape.front()[0] - centre[0], dy = lane.shape.front()[1] - centre[1];
  if (std::abs(dy) >= std::abs(dx)) return dy > 0 ? kNorth : kSouth;
  return dx > 0 ? kEast : kWest;
}

std::array<double, 2> junction_centre(const TrafficLightProgram& light,
                                      const NetworkGeometry& geometry) {
  if (const auto it = geometry.junctions.find(light.id); it != geometry.junctions.end())
    return it->second;
  std::array<double, 2> sum{0, 0};  // a light named unlike its junction: its stop lines' middle
  for (const std::string& id : light.incoming_lanes) {
    sum[0] += geometry.lane(id).shape.back()[0] / static_cast<double>(light.incoming_lanes.size());
    sum[1] += geometry.lane(id).shape.back()[1] / static_cast<double>(light.incoming_lanes.size());
  }
  return sum;
}

std::string approach_state(const ApproachLayout& layout, int approach, char lit) {
  std::string state(layout.link_approach.size(), 'r');
  for (size_t i = 0; i < state.size(); ++i)
    if (layout.link_approach[i] == approach) state[i] = lit;
  return state;
}

}  // namespace

ApproachLayout read_approaches(const TrafficLightProgram& light, const NetworkGeometry& geometry) {
  const std::array<double, 2> centre = junction_centre(light, geometry);
  ApproachLayout layout;
  // One state character per signal index: the program's state length (TraCI's controlled links).
  const size_t states = light.phases.empty() ? static_cast<size_t>(light.num_links)
                                             : light.phases.front().state.size();
  layout.link_approach.assign(std::max(states, static_cast<size_t>(light.num_links)), -1);
  for (const SignalLink& link : light.links)
    layout.link_approach[static_cast<size_t>(link.index)] =
        approach_of(geometry.lane(link.from), centre);
  for (const std::string& id : light.incoming_lanes) {  // link-index order
    const LaneGeometry& lane = geometry.lane(id);
    const int approach = approach_of(lane, centre);
    layout.capacity[approach] += lane.length / kVehicleSpace;
    layout.limit[approach] = std::max(layout.limit[approach], lane.speed);
    if (std::find(layout.edges.begin(), layout.edges.end(), lane.edge) == layout.edges.end()) {
      layout.edges.push_back(lane.edge);
      layout.edge_approach.push_back(approach);
    }
  }
  return layout;
}

SignalControl approach_signal_control(const ApproachLayout& layout) {
  SignalControl control;
  for (int a = 0; a < kNumApproaches; ++a)
    control.green_states.push_back(approach_state(layout, a, 'G'));
  for (int from = 0; from < kNumApproaches; ++from) {
    control.yellow_states.emplace_back(kNumApproaches, approach_state(layout, from, 'y'));
    control.yellow_states.back()[from].clear();
  }
  return control;
}

}  // namespace rlrun::traffic
