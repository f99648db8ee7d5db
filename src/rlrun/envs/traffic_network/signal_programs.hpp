#pragma once
// The traffic lights of a SUMO network, read from its .net.xml before SUMO runs (issue 21's
// TrafficNetwork-v0 builds one agent per light from these), and the control an RL agent gets
// over one light, with sumo-rl's semantics (sumo_rl/environment/traffic_signal.py,
// TrafficSignal.build_phases):
//
// * the agent's actions are the light's green phases: the phases of its program, in program
//   order, whose state has no 'y' and is not all red ('r' / 's');
// * switching from green i to green j shows a yellow state for yellow_time first: green i's
//   state with 'y' wherever a 'G' / 'g' of green i becomes 'r' / 's' in green j;
// * the agent sees the light's incoming lanes (the `from` lanes of the connections the light
//   controls, in link-index order, each once: TraCI's getControlledLanes de-duplicated) and
//   its outgoing lanes (their `to` lanes, each once; sumo-rl keeps them in a Python set, here
//   in link-index order so that the observation order is reproducible).
//
// Reading is strict: a file that is not a SUMO network, a light without a green phase, or a
// `ts_ids` entry naming no light is a clear error (with a did-you-mean), never a crash.
#include <string>
#include <vector>

namespace rlrun::traffic {

struct SignalPhase {
  double duration = 0;  // seconds, as in the net file
  std::string state;    // one character per controlled link: r y g G s u o O
};

struct SignalLink {
  int index = 0;         // position in the phase states
  std::string from, to;  // incoming and outgoing lane
};

struct TrafficLightProgram {
  std::string id;
  std::string program_id;
  std::vector<SignalPhase> phases;          // the first program of this light in the file
  std::vector<std::string> incoming_lanes;  // controlled lanes, link-index order, unique
  std::vector<std::string> outgoing_lanes;  // lanes they lead to, link-index order, unique
  int num_links = 0;                        // controlled link indices (state length)
  std::vector<SignalLink> links;            // by link index
};

// Every light of a network file (tlLogic elements joined with the connections they control),
// in the file's order. Throws ConfigError naming the file for a missing or malformed file, a
// file with no <net> root, or a light whose phases' states do not all have one character per
// controlled link.
std::vector<TrafficLightProgram> read_signal_programs(const std::string& net_file);

// The lights that become agents: all of them when `ts_ids` is empty, else those named, in
// `ts_ids` order. Throws ConfigError when the network has no traffic light, or for an id that
// names no light (did-you-mean, and the ids there are).
std::vector<TrafficLightProgram> select_lights(const std::vector<TrafficLightProgram>& lights,
                                               const std::vector<std::string>& ts_ids,
                                               const std::string& net_file);

struct SignalControl {
  std::vector<std::string> green_states;                // the agent's actions
  std::vector<std::vector<std::string>> yellow_states;  // [from][to], empty on the diagonal
};

// sumo-rl's build_phases for one light. Throws ConfigError when the program has no green
// phase (nothing for an agent to choose).
SignalControl derive_signal_control(const TrafficLightProgram& light);

}  // namespace rlrun::traffic
