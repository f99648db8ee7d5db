#pragma once
// A traffic scenario (scenarios/*.yaml) for both traffic envs (TrafficSignal-v0's has one
// light): any SUMO network with its demand, named either as SUMO's own input files
//
//   name: grid4x4
//   description: 16 signalised junctions, one hour of demand
//   net_file: ../sumo_data/grid4x4/grid4x4.net.xml
//   route_files: [../sumo_data/grid4x4/grid4x4.rou.xml]
//   additional_files: []        # optional: detectors, vehicle types, other programs
//   begin: 0                    # simulated seconds
//   end: 3600
//
// or as a SUMO configuration (`sumocfg: city.sumocfg`, whose <input> names the files and whose
// <time> gives begin / end unless the YAML sets them). Paths are relative to the file that
// names them. A bare .sumocfg may be given instead of a YAML file.
//
// Everything that can be checked before SUMO runs is checked here, with a clear error: missing
// files, begin >= end, route files whose routes name edges the network does not have (SUMO
// would otherwise stop mid-episode or drop the vehicles with only a warning).
#include <map>
#include <string>
#include <vector>

namespace rlrun::traffic {

struct NetworkScenario {
  std::string name;
  std::string description;
  std::string sumocfg;                        // as written
  std::string net_file;                       // as written
  std::vector<std::string> route_files;       // as written
  std::vector<std::string> additional_files;  // as written
  double begin = -1;                          // -1: from the sumocfg, else 0
  double end = -1;                            // -1: from the sumocfg, else 3600
  double scale = 1.0;

  template <class V>
  void visit(V& v) {
    v("name", name, "the scenario's name");
    v("description", description, "what it simulates");
    v("sumocfg", sumocfg, "a SUMO configuration naming the files (instead of net_file, ...)");
    v("net_file", net_file, "the SUMO network (.net.xml), relative to this file");
    v("route_files", route_files, "the demand (.rou.xml files), relative to this file");
    v("additional_files", additional_files, "SUMO additional files (detectors, vTypes, ...)");
    v("begin", begin, "simulated second the episode starts at (default: the sumocfg's, else 0)");
    v("end", end, "simulated second the episode ends at (default: the sumocfg's, else 3600)");
    v("scale", scale, "demand multiplier (the env's scale multiplies it)");
  }

  // Resolved by load_network_scenario: absolute or working-directory-relative paths.
  struct Files {
    std::string sumocfg;  // empty when the scenario names the files itself
    std::string net;
    std::vector<std::string> routes;
    std::vector<std::string> additionals;
  } files;
};

// `path` is a scenario .yaml or a bare .sumocfg. A relative path that does not exist from the
// working directory is also looked for in rlrun's shipped data (find_data_file). Throws
// ConfigError (file:line:col where there is one) for a bad scenario, RuntimeFailure for a
// missing file.
NetworkScenario load_network_scenario(const std::string& path);

// SUMO's input arguments for the scenario: `-c CFG` or `-n NET -r R1,R2 -a A1`, then `--begin`,
// `--end` (the episode's), without seed, scale or outputs. `more_additionals` are loaded after
// the scenario's own (with a sumocfg: `-a` naming its files and these, the rest of the
// configuration kept).
std::vector<std::string> scenario_arguments(const NetworkScenario& scenario,
                                            const std::vector<std::string>& more_additionals = {});

// Every edge id that the route files' <route edges>, <trip>/<flow>/<vehicle> from/to/via name
// must be an edge of the network (`edges`), and each edge of a <route> must lead to the next
// (`successors`: the net's connections). Throws ConfigError naming the route file, its line
// and the first edge that does not fit.
void check_routes_fit(const std::vector<std::string>& route_files,
                      const std::vector<std::string>& edges,
                      const std::map<std::string, std::vector<std::string>>& successors);

}  // namespace rlrun::traffic
