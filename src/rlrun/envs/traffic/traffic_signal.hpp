#pragma once
// TrafficSignal-v0: one traffic light at a 4-arm intersection simulated by the real SUMO (the
// course's third task; sumo-rl's TrafficSignal and SumoEnvironment, LucasAlegre/sumo-rl,
// sumo_rl/environment/traffic_signal.py and env.py, are the reference).
//
//   action  Discrete(4): green for the North, South, East or West approach alone (its
//           through, left and right movements). Switching inserts `yellow_time` seconds of
//           yellow for the old approach; a green lasts at least `min_green` seconds (a switch
//           asked for earlier keeps the current green), as sumo-rl.
//   step    `delta_time` simulated seconds (yellow included) in one TraCI round trip (three
//           when the light switches), subscriptions bringing back the state.
//   obs     Box(10) in [0, 1]: halting vehicles per approach / the approach's capacity (N, S,
//           E, W), mean speed per approach / speed limit, current green / 3, seconds since the
//           last change / max_green (clipped).
//   reward  `queue` (default): -(halting vehicles on the incoming lanes); sumo-rl's
//           `diff-waiting-time` (drop in the accumulated waiting time of the vehicles on the
//           incoming lanes, / 100), `average-speed` (mean speed / limit of those vehicles, 1
//           when none) and `pressure` (vehicles on outgoing minus incoming lanes).
//   episode truncated after `num_seconds` simulated seconds; every reset restarts SUMO
//           (seeded: the reset's seed, else the next draw of the env's stream).
//   info    total_queue_length (halting now), sim_time; at the episode's last step also the
//           trip metrics, from SUMO's own tripinfo output read when SUMO closes: throughput
//           (vehicles arrived), avg_waiting_time and avg_travel_time (their means; waiting =
//           seconds below 0.1 m/s). They are 0 before: SUMO writes them only then, and
//           tracking every vehicle every second instead would halve the speed.
//   backend traci (a sumo process, TCP) or libsumo (SUMO inside rlrun, one env per process).
#include <array>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "rlrun/core/config_checks.hpp"
#include "rlrun/core/private_temp_dir.hpp"
#include "rlrun/core/trusted_values.hpp"
#include "rlrun/env.hpp"
#include "rlrun/env_seeding.hpp"
#include "rlrun/envs/traffic/sumo_connection.hpp"
#include "rlrun/envs/traffic/traffic_scenario.hpp"
#include "rlrun/info.hpp"
#include "rlrun/space.hpp"

namespace rlrun {

class TrafficSignal : public Env {
 public:
  struct Config {
    SimulatorInput scenario;        // scenarios/*.yaml or a .sumocfg; empty = the shipped one
    std::string backend = "traci";  // traci (a sumo process, socket) or libsumo (in-process)
    ProgramPath sumo_binary{"sumo"};
    bool gui = false;                 // run sumo-gui instead
    double scale = 1.0;               // demand multiplier
    int delta_time = 5;               // simulated seconds per action
    int yellow_time = 3;              // seconds of yellow on every switch
    int min_green = 5;                // a green lasts at least this long
    int max_green = 60;               // normalisation of the phase time in the observation
    int num_seconds = 3600;           // episode length in simulated seconds
    std::string reward_fn = "queue";  // queue, diff-waiting-time, average-speed, pressure
    OutputPath tripinfo_output;       // also write SUMO's tripinfo XML here (tests, analysis)

    template <class V>
    void visit(V& v) {
      v("scenario", scenario,
        "scenario file (scenarios/*.yaml) or SUMO .sumocfg; empty = "
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
      v("max_green", max_green, "phase time that maps to 1 in the observation", in_range(1, 86400));
      v("num_seconds", num_seconds, "episode length in simulated seconds",
        in_range(1, 365 * 86400));
      v("reward_fn", reward_fn, "queue | diff-waiting-time | average-speed | pressure",
        OneOf{{"queue", "diff-waiting-time", "average-speed", "pressure"}});
      v("tripinfo_output", tripinfo_output, "also write SUMO's tripinfo XML to this file");
    }
  };

  enum Approach : int { kNorth = 0, kSouth, kEast, kWest, kNumApproaches };
  enum class Reward { kQueue, kDiffWaitingTime, kAverageSpeed, kPressure };

  TrafficSignal() : TrafficSignal(Config{}) {}
  // Throws std::invalid_argument for inconsistent timings or an unknown reward_fn.
  explicit TrafficSignal(const Config& config);
  ~TrafficSignal() override;

  const Space& observation_space() const override { return observation_space_; }
  const Space& action_space() const override { return action_space_; }
  const Info& info() const override { return info_; }
  std::string id() const override { return "TrafficSignal-v0"; }

  void reset(std::optional<uint64_t> seed, std::span<float> obs) override;
  StepResult step(std::span<const float> action, std::span<float> obs) override;

  const Config& config() const { return config_; }
  // The light: the approach that has green (a switch's yellow ends within the step).
  int green_approach() const { return green_; }
  double sim_time() const { return sim_time_; }
  // A top-down picture of the roads, the vehicles (red when waiting) and the light at each
  // stop line (traffic_signal_render.cpp); 10 frames per second of video, one per decision.
  RenderSpec render_spec() const override { return {600, 600, 10.0}; }
  bool render(Frame& frame) const override;

  // The running SUMO's process id (-1 before the first reset), for tests.
  pid_t sumo_pid() const { return sumo_ ? sumo_->pid() : -1; }

  const TrafficScenario& scenario() const { return scenario_; }

 private:
  struct Lane : SumoLaneShape {
    int approach = -1;  // for incoming lanes
  };
  struct Road {  // a SUMO edge: what the subscriptions count
    std::string edge;
    int approach = -1;  // for incoming roads
    SumoLaneCounts counts;
  };

  void start_simulation(uint64_t sumo_seed);
  // Runs `seconds` of simulation in one call and takes in the subscriptions' news.
  void advance(int seconds);
  // The signal state string: `approach` green (or yellow), every other link red.
  std::string light_state(int approach, bool yellow) const;
  // The episode's last step: SUMO closes, its tripinfo output gives the trip metrics.
  void finish_episode();
  void write_observation(std::span<float> obs) const;
  double reward();
  // diff-waiting-time and average-speed look at every vehicle near the junction.
  bool needs_vehicles() const {
    return reward_ == Reward::kDiffWaitingTime || reward_ == Reward::kAverageSpeed;
  }
  void update_info();
  [[noreturn]] void sumo_failed(const std::exception& e) const;

  Config config_;
  Reward reward_;  // config_.reward_fn, parsed once
  TrafficScenario scenario_;
  Space observation_space_;
  Space action_space_;
  Info info_;
  EnvSeeding seeding_;  // Gymnasium's seeding rules; SUMO's seeds come from its stream
  std::unique_ptr<SumoConnection> sumo_;
  std::string tls_;  // the traffic light's id in the scenario

  std::vector<Lane> incoming_, outgoing_;
  std::vector<Road> incoming_roads_, outgoing_roads_;  // outgoing: for the pressure reward
  std::vector<int> link_approach_;        // approach of each signal link (by link index)
  double capacity_[kNumApproaches] = {};  // vehicles that fit on an approach's lanes
  double limit_[kNumApproaches] = {};     // an approach's speed limit
  int green_ = kNorth;
  int since_change_ = 0;  // seconds since the last light change
  double sim_time_ = 0;
  // The last advance's news: lane counts and, when subscribed, the vehicles. render() may
  // subscribe to the vehicles (it is const, like Gymnasium's render(); the simulation is not
  // changed by it).
  mutable SumoState state_;
  mutable bool vehicles_subscribed_ = false;
  bool finished_ = false;  // SUMO closed at the episode's end
  // SUMO's tripinfo at the episode's end: vehicles arrived, their mean waiting and travel time.
  int throughput_ = 0;
  double avg_waiting_ = 0, avg_travel_ = 0;
  std::string tripinfo_path_;  // config.tripinfo_output, else a file in tripinfo_dir_
  std::unique_ptr<PrivateTempDir> tripinfo_dir_;  // private; goes with the env
  double last_waiting_sum_ = 0;                   // diff-waiting-time
  int key_waiting_, key_travel_, key_queue_, key_throughput_, key_time_;
  bool has_state_ = false;
};

}  // namespace rlrun
