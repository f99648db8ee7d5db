#pragma once
// TrafficSignal-v0: one traffic light at a 4-arm intersection simulated by the real SUMO (the
// course's third task; sumo-rl's TrafficSignal and SumoEnvironment, LucasAlegre/sumo-rl,
// sumo_rl/environment/traffic_signal.py and env.py, are the reference). It is TrafficNetwork-v0's
// single-intersection case — the same code (envs/traffic_network/: the light's rules, its
// observation and reward functions; envs/sumo/: the SUMO backend) on a scenario with one
// light, with these settings:
//
//   action  Discrete(4) (phases: approaches): green for the North, South, East or West
//           approach alone (its through, left and right movements). Switching inserts
//           `yellow_time` seconds of yellow for the old approach; a green lasts at least
//           `min_green` seconds (a switch asked for earlier keeps the current green), as
//           sumo-rl; `max_green` is not enforced (sumo-rl's rule).
//   step    `delta_time` simulated seconds (yellow included) in one TraCI round trip (two
//           when the light switches), subscriptions bringing back the state.
//   obs     `observation: approach` (default), Box(10) in [0, 1]: halting vehicles per approach
//           / the approach's capacity (N, S, E, W), mean speed per approach / speed limit,
//           current green / 3, seconds since the green began / max_green (clipped); or
//           `observation: sumo-rl`, sumo-rl's (envs/traffic_network/light_agent.hpp).
//   reward  `reward_fn`, the one set of both envs (light_agent.hpp): diff-waiting-time (the
//           default, sumo-rl's: drop of the waiting time accumulated on the incoming lanes,
//           / 100), queue (-halting vehicles on the incoming lanes), average-speed, pressure.
//   episode truncated after `num_seconds` simulated seconds of decisions (the reset simulates a
//           first second before them); every reset restarts SUMO (seeded: the reset's seed,
//           else the next draw of the env's stream).
//   info    total_queue_length (halting now), sim_time; at the episode's last step also the
//           trip metrics, from SUMO's own tripinfo output read when SUMO closes: throughput
//           (vehicles arrived), avg_waiting_time and avg_travel_time (their means; waiting =
//           seconds below 0.1 m/s).
//   backend traci (a sumo process, TCP; the default) or libsumo (SUMO inside rlrun, one env
//           per process).
#include <string>

#include "rlrun/core/config_checks.hpp"
#include "rlrun/core/trusted_values.hpp"
#include "rlrun/envs/traffic_network/traffic_network.hpp"

namespace rlrun {

class TrafficSignal : public TrafficNetwork {
 public:
  struct Config {
    SimulatorInput scenario;  // scenarios/*.yaml or a .sumocfg; empty = the shipped one
    std::string backend = "traci";
    ProgramPath sumo_binary{"sumo"};
    bool gui = false;
    double scale = 1.0;
    int delta_time = 5;
    int yellow_time = 3;
    int min_green = 5;
    int max_green = 60;  // normalisation of the green's age in the approach observation
    int num_seconds = 3600;
    std::string reward_fn = "diff-waiting-time";  // the one default of both envs
    std::string observation = "approach";
    OutputPath tripinfo_output;

    template <class V>
    void visit(V& v) {
      v("scenario", scenario,
        "scenario file (scenarios/*.yaml) or SUMO .sumocfg with one traffic light; empty = "
        "scenarios/single_intersection.yaml");
      v("backend", backend,
        "traci (a sumo process over a socket) or libsumo (SUMO inside rlrun: faster, one env "
        "per process)",
        OneOf{{"traci", "libsumo"}});
      v("sumo_binary", sumo_binary, "the sumo program to run (Debian package 'sumo')");
      v("gui", gui, "run sumo-gui to watch the simulation");
      v("scale", scale, "demand multiplier (SUMO --scale, times the scenario's scale)",
        in_range(0.0, 1000.0).open_low());
      v("delta_time", delta_time, "simulated seconds per action", in_range(1, 86400));
      v("yellow_time", yellow_time, "seconds of yellow inserted on every switch",
        in_range(0, 86400));
      v("min_green", min_green, "minimum green time in seconds", in_range(0, 86400));
      v("max_green", max_green, "green age that maps to 1 in the approach observation",
        in_range(1, 86400));
      v("num_seconds", num_seconds, "episode length in simulated seconds",
        in_range(1, 365 * 86400));
      v("reward_fn", reward_fn,
        "diff-waiting-time (sumo-rl's, the default) | queue | pressure | average-speed",
        OneOf{traffic::reward_function_names()});
      v("observation", observation,
        "approach (Box(10): queue and speed per approach N, S, E, W, the green, its age) or "
        "sumo-rl (green one-hot, min-green flag, lane densities and queues)",
        OneOf{traffic::observation_function_names()});
      v("tripinfo_output", tripinfo_output, "also write SUMO's tripinfo XML to this file");
    }
  };

  // TrafficSignal-v0's settings as TrafficNetwork-v0's: one light, phases: approaches,
  // max_green not enforced, SUMO driven from rlrun itself (own_process: false), and the
  // episode's end num_seconds after the reset's first second.
  static TrafficNetwork::Config network_config(const Config& config);

  TrafficSignal() : TrafficSignal(Config{}) {}
  // Throws std::invalid_argument for inconsistent timings or an unknown reward_fn, ConfigError
  // for a scenario whose network has not exactly one traffic light.
  explicit TrafficSignal(const Config& config);

  const Config& config() const { return config_; }
  // The light: the approach that has green (a switch's yellow ends within the step).
  int green_approach() const { return agents().front().green(); }
  RenderSpec render_spec() const override { return {600, 600, 10.0}; }

 private:
  Config config_;
};

}  // namespace rlrun
