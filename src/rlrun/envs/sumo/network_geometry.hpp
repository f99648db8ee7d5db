#pragma once
// The roads of a SUMO network as the agents and the picture need them, read from its .net.xml
// before SUMO runs: every lane's length, speed limit, width and centre line, the edges (for
// checking route files), and where each junction is (rendering zooms to one).
#include <array>
#include <map>
#include <string>
#include <vector>

namespace rlrun::traffic {

struct LaneGeometry {
  std::string id;
  std::string edge;
  double length = 0, speed = 0, width = 3.2;
  std::vector<std::array<double, 2>> shape;  // centre line, metres
  bool internal = false;                     // inside a junction (SUMO's ':' lanes)
};

struct NetworkGeometry {
  std::vector<LaneGeometry> lanes;                         // file order
  std::map<std::string, size_t> lane_index;                // id -> position in `lanes`
  std::vector<std::string> edges;                          // the non-internal edges
  std::map<std::string, std::array<double, 2>> junctions;  // id -> position
  std::array<double, 4> bounds{0, 0, 1, 1};                // x0, y0, x1, y1 of the lanes
  // Where each edge's traffic can go next (the net's <connection>s between normal edges).
  std::map<std::string, std::vector<std::string>> edge_successors;

  const LaneGeometry& lane(const std::string& id) const;  // throws ConfigError if absent
};

// Throws ConfigError naming the file for a file that is not a SUMO network.
NetworkGeometry read_network_geometry(const std::string& net_file);

}  // namespace rlrun::traffic
