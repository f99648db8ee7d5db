#pragma once
// A light's approaches — North, South, East, West — for the intersection-style control and
// observation (`phases: approaches`, `observation: approach`; TrafficSignal-v0's defaults, the
// course's traffic task): each incoming lane belongs to the approach its far end lies in, seen
// from the junction, and each approach can be given green alone.
#include <array>
#include <string>
#include <vector>

#include "rlrun/envs/sumo/network_geometry.hpp"
#include "rlrun/envs/traffic_network/signal_programs.hpp"

namespace rlrun::traffic {

enum Approach : int { kNorth = 0, kSouth, kEast, kWest, kNumApproaches };

struct ApproachLayout {
  std::vector<int> link_approach;  // per link index (state position): its incoming lane's, or -1
  std::vector<std::string> edges;  // the incoming lanes' roads, in the order of their lanes
  std::vector<int> edge_approach;  // per road
  std::array<double, kNumApproaches> capacity{};  // vehicles that fit on an approach's lanes
  std::array<double, kNumApproaches> limit{};     // an approach's speed limit, m/s
};

// The approaches of `light`, whose junction is `geometry`'s junction of the light's id (else
// the middle of its stop lines). Capacity: lane length / 7.5 m (a 5 m car and its 2.5 m gap).
ApproachLayout read_approaches(const TrafficLightProgram& light, const NetworkGeometry& geometry);

// One green per approach, in N, S, E, W order: that approach's links 'G', every other 'r'; the
// switch from approach i shows i's links yellow ('y'), every other red.
SignalControl approach_signal_control(const ApproachLayout& layout);

}  // namespace rlrun::traffic
