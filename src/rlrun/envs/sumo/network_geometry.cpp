#include "rlrun/envs/sumo/network_geometry.hpp"

#include <algorithm>
#include <limits>
#include <sstream>

#include "rlrun/core/errors.hpp"
#include "rlrun/core/quoted_text.hpp"
#include "rlrun/envs/sumo/net_file.hpp"

namespace rlrun::traffic {

namespace {

// SUMO's shape attribute: "x1,y1 x2,y2 ...".
std::vector<std::array<double, 2>> parse_shape(const char* text) {
  std::vector<std::array<double, 2>> shape;
  std::istringstream in(text);
  std::string point;
  while (in >> point) {
    const size_t comma = point.find(',');
    if (comma == std::string::npos) continue;
    shape.push_back(
        {std::strtod(point.c_str(), nullptr), std::strtod(point.c_str() + comma + 1, nullptr)});
  }
  return shape;
}

}  // namespace

const LaneGeometry& NetworkGeometry::lane(const std::string& id) const {
  const auto it = lane_index.find(id);
  if (it == lane_index.end())
    throw ConfigError("the network has no lane '" + quoted_text(id) + "'");
  return lanes[it->second];
}

NetworkGeometry read_network_geometry(const std::string& net_file) {
  pugi::xml_document doc;
  const pugi::xml_node net = load_net_file(net_file, doc);
  NetworkGeometry g;
  double x0 = std::numeric_limits<double>::infinity(), y0 = x0, x1 = -x0, y1 = -x0;
  for (const pugi::xml_node edge : net.children("edge")) {
    const std::string edge_id = edge.attribute("id").as_string();
    const bool internal = std::string(edge.attribute("function").as_string()) == "internal";
    if (!internal) g.edges.push_back(edge_id);
    for (const pugi::xml_node l : edge.children("lane")) {
      LaneGeometry lane;
      lane.id = l.attribute("id").as_string();
      lane.edge = edge_id;
      lane.length = l.attribute("length").as_double();
      lane.speed = l.attribute("speed").as_double();
      lane.width = l.attribute("width").as_double(3.2);
      lane.shape = parse_shape(l.attribute("shape").as_string());
      lane.internal = internal;
      for (const auto& p : lane.shape) {
        x0 = std::min(x0, p[0]), x1 = std::max(x1, p[0]);
        y0 = std::min(y0, p[1]), y1 = std::max(y1, p[1]);
      }
      g.lane_index[lane.id] = g.lanes.size();
      g.lanes.push_back(std::move(lane));
    }
  }
  for (const pugi::xml_node j : net.children("junction"))
    if (std::string(j.attribute("type").as_string()) != "internal")
      g.junctions[j.attribute("id").as_string()] = {j.attribute("x").as_double(),
                                                    j.attribute("y").as_double()};
  for (const pugi::xml_node c : net.children("connection")) {
    const std::string from = c.attribute("from").as_string(), to = c.attribute("to").as_string();
    if (from.empty() || to.empty() || from[0] == ':' || to[0] == ':') continue;
    std::vector<std::string>& next = g.edge_successors[from];
    if (std::find(next.begin(), next.end(), to) == next.end()) next.push_back(to);
  }
  if (x0 <= x1 && y0 <= y1) g.bounds = {x0, y0, x1, y1};
  return g;
}

}  // namespace rlrun::traffic
