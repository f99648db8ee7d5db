#include "rlrun/envs/traffic_network/signal_programs.hpp"

#include <algorithm>
#include <map>

#include "rlrun/core/config_node.hpp"
#include "rlrun/core/errors.hpp"
#include "rlrun/core/quoted_text.hpp"
#include "rlrun/envs/sumo/net_file.hpp"

namespace rlrun::traffic {

namespace {

void add_unique(std::vector<std::string>& list, const std::string& item) {
  if (std::find(list.begin(), list.end(), item) == list.end()) list.push_back(item);
}

bool is_green(const std::string& state) {
  // sumo-rl: `'y' not in state and state.count('r') + state.count('s') != len(state)`.
  if (state.find('y') != std::string::npos) return false;
  return std::any_of(state.begin(), state.end(), [](char c) { return c != 'r' && c != 's'; });
}

}  // namespace

std::vector<TrafficLightProgram> read_signal_programs(const std::string& net_file) {
  pugi::xml_document doc;
  const pugi::xml_node net = load_net_file(net_file, doc);

  std::vector<TrafficLightProgram> lights;
  std::map<std::string, size_t> index;  // light id -> position in `lights`
  for (const pugi::xml_node logic : net.children("tlLogic")) {
    const std::string id = logic.attribute("id").as_string();
    if (id.empty()) throw ConfigError(net_file + ": a <tlLogic> without an id");
    if (index.count(id)) continue;  // later programs of the same light: SUMO starts the first
    TrafficLightProgram light;
    light.id = id;
    light.program_id = logic.attribute("programID").as_string();
    for (const pugi::xml_node phase : logic.children("phase"))
      light.phases.push_back(
          {phase.attribute("duration").as_double(), phase.attribute("state").as_string()});
    index[id] = lights.size();
    lights.push_back(std::move(light));
  }

  // The connections each light controls, by link index.
  std::map<std::string, std::map<int, std::pair<std::string, std::string>>> links;
  for (const pugi::xml_node c : net.children("connection")) {
    const pugi::xml_attribute tl = c.attribute("tl");
    if (!tl) continue;
    const std::string lane_in =
        std::string(c.attribute("from").as_string()) + "_" + c.attribute("fromLane").as_string();
    const std::string lane_out =
        std::string(c.attribute("to").as_string()) + "_" + c.attribute("toLane").as_string();
    links[tl.as_string()][c.attribute("linkIndex").as_int(-1)] = {lane_in, lane_out};
  }
  for (TrafficLightProgram& light : lights) {
    for (const auto& [link, lanes] : links[light.id]) {
      if (link < 0)
        throw ConfigError(net_file + ": light " + quoted_text(light.id) +
                          " has a connection without a linkIndex");
      light.num_links = std::max(light.num_links, link + 1);
      add_unique(light.incoming_lanes, lanes.first);
      add_unique(light.outgoing_lanes, lanes.second);
      light.links.push_back({link, lanes.first, lanes.second});
    }
    for (const SignalPhase& phase : light.phases)
      if (static_cast<int>(phase.state.size()) < light.num_links)
        throw ConfigError(net_file + ": light " + quoted_text(light.id) + " has a phase state '" +
                          quoted_text(phase.state) + "' for " + std::to_string(light.num_links) +
                          " controlled links");
  }
  return lights;
}

std::vector<TrafficLightProgram> select_lights(const std::vector<TrafficLightProgram>& lights,
                                               const std::vector<std::string>& ts_ids,
                                               const std::string& net_file) {
  if (lights.empty())
    throw ConfigError(net_file +
                      ": the network has no traffic light, so there is no agent (add "
                      "lights with netconvert --tls.guess or --tls.set)");
  if (ts_ids.empty()) return lights;
  std::vector<std::string> ids;
  for (const TrafficLightProgram& light : lights) ids.push_back(light.id);
  std::vector<TrafficLightProgram> out;
  for (const std::string& id : ts_ids) {
    const auto it = std::find(ids.begin(), ids.end(), id);
    if (it == ids.end()) {
      std::string all;
      for (size_t k = 0; k < ids.size() && k < 20; ++k)
        all += (k ? ", " : "") + quoted_text(ids[k], 60);
      if (ids.size() > 20) all += ", ...";
      throw ConfigError("ts_ids: '" + id + "' is not a traffic light of " + net_file +
                        quoted_text(did_you_mean(id, ids), 300) + " (its lights: " + all + ")");
    }
    out.push_back(lights[static_cast<size_t>(it - ids.begin())]);
  }
  return out;
}

SignalControl derive_signal_control(const TrafficLightProgram& light) {
  SignalControl control;
  for (const SignalPhase& phase : light.phases)
    if (is_green(phase.state)) control.green_states.push_back(phase.state);
  if (control.green_states.empty())
    throw ConfigError("traffic light " + quoted_text(light.id) +
                      ": its program has no green phase, so an agent "
                      "has nothing to choose (leave it out of ts_ids)");
  const size_t n = control.green_states.size();
  control.yellow_states.assign(n, std::vector<std::string>(n));
  for (size_t i = 0; i < n; ++i)
    for (size_t j = 0; j < n; ++j) {
      if (i == j) continue;
      const std::string& from = control.green_states[i];
      const std::string& to = control.green_states[j];
      std::string yellow = from;
      for (size_t s = 0; s < from.size() && s < to.size(); ++s)
        if ((from[s] == 'G' || from[s] == 'g') && (to[s] == 'r' || to[s] == 's')) yellow[s] = 'y';
      control.yellow_states[i][j] = yellow;
    }
  return control;
}

}  // namespace rlrun::traffic
