#pragma once
// A traffic scenario file (scenarios/*.yaml): which SUMO network and demand TrafficSignal-v0
// simulates. It names a .sumocfg (relative to the YAML file) and the scenario's demand scale,
// which the env's own `scale` multiplies (so `scale: 1.5` on the rush-hour scenario means 1.5 x
// its demand). Unknown keys are errors with file:line:column and the closest valid key.
//
//   name: single_intersection
//   description: one 4-arm intersection, busy north-south, quiet east-west
//   sumocfg: ../sumo_data/single_intersection/single.sumocfg
//   scale: 1.0
#include <string>

namespace rlrun {

struct TrafficScenario {
  std::string name;
  std::string description;
  std::string sumocfg;  // as written: relative to the scenario file
  double scale = 1.0;

  template <class V>
  void visit(V& v) {
    v("name", name, "the scenario's name");
    v("description", description, "what it simulates");
    v("sumocfg", sumocfg, "the SUMO configuration, relative to this file");
    v("scale", scale, "demand multiplier of the scenario (the env's scale multiplies it)");
  }

  std::string sumocfg_path;  // resolved
};

// The shipped default: scenarios/single_intersection.yaml in shipped_data_dir().
std::string default_traffic_scenario();

// `path` is a scenario .yaml or a bare .sumocfg (scale 1). A relative path that does not exist
// from the working directory is also looked for in rlrun's shipped data (find_data_file), so
// `scenario: scenarios/single_intersection_rush.yaml` works from anywhere. Throws ConfigError
// for a bad file, RuntimeFailure for a missing one.
TrafficScenario load_traffic_scenario(const std::string& path);

}  // namespace rlrun
