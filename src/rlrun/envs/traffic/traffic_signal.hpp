#pragma once
// TrafficSignal-v0: one traffic light at a 4-arm intersection simulated by the real SUMO (the
// course's third task; sumo-rl's TrafficSignal and SumoEnvironment, LucasAlegre/sumo-rl,
// sumo_rl/environment/traffic_signal.py and env.py, are the reference).
//
//   action  Discrete(4): green for the North, South, East or West approach alone (its
//           through, left and right movements). Switching inserts `yellow_time` seconds of
//           yellow for the old approach; a green lasts at least `min_green` seconds (a switch
//           asked for earlier keeps the current green), as sumo-rl.
//   step    `delta_time` simulated seconds (yellow included), one TraCI round trip per
//           simulated second thanks to subscriptions.
//   obs     Box(10) in [0, 1]: halting vehicles per approach / the approach's capacity (N, S,
//           E, W), mean speed per approach / speed limit, current green / 3, seconds since the
//           last change / max_green (clipped).
//   reward  `queue` (default): -(halting vehicles on the incoming lanes); sumo-rl's
//           `diff-waiting-time` (drop in the accumulated waiting time of the vehicles on the
//           incoming lanes, / 100), `average-speed` (mean speed / limit of those vehicles, 1
//           when none) and `pressure` (vehicles on outgoing minus incoming lanes).
//   episode truncated after `num_seconds` simulated seconds; every reset restarts SUMO
//           (seeded: the reset's seed, else the next draw of the env's stream).
//   info    avg_waiting_time, avg_travel_time (means over the vehicles that arrived this
//           episode, as SUMO's tripinfo output computes them: waiting = seconds at < 0.1 m/s),
//           throughput (vehicles arrived), total_queue_length (halting now), sim_time.
#include <array>
#include <map>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "rlrun/core/rng.hpp"
#include "rlrun/core/space.hpp"
#include "rlrun/env/env.hpp"
#include "rlrun/env/info.hpp"
#include "rlrun/envs/traffic/sumo_process.hpp"

// SUMO's TraCI client (libtraci namespace; it must be included as libtraci.h, which selects it).
#include <libsumo/libtraci.h>

namespace rlrun {

class TrafficSignal : public Env {
 public:
  struct Config {
    std::string scenario;         // .sumocfg; empty = the shipped single intersection
    std::string sumo_binary = "sumo";
    bool gui = false;             // run sumo-gui instead
    double scale = 1.0;           // demand multiplier
    int delta_time = 5;           // simulated seconds per action
    int yellow_time = 3;          // seconds of yellow on every switch
    int min_green = 5;            // a green lasts at least this long
    int max_green = 60;           // normalisation of the phase time in the observation
    int num_seconds = 3600;       // episode length in simulated seconds
    std::string reward_fn = "queue";  // queue, diff-waiting-time, average-speed, pressure
    std::string tripinfo_output;  // also write SUMO's tripinfo XML here (tests, analysis)

    template <class V>
    void visit(V& v) {
      v("scenario", scenario, "SUMO .sumocfg file; empty = sumo_data/single_intersection");
      v("sumo_binary", sumo_binary, "the sumo program to run (Debian package 'sumo')");
      v("gui", gui, "run sumo-gui to watch the simulation");
      v("scale", scale, "demand multiplier (SUMO --scale)");
      v("delta_time", delta_time, "simulated seconds per action");
      v("yellow_time", yellow_time, "seconds of yellow inserted on every switch");
      v("min_green", min_green, "minimum green time in seconds");
      v("max_green", max_green, "phase time that maps to 1 in the observation");
      v("num_seconds", num_seconds, "episode length in simulated seconds");
      v("reward_fn", reward_fn, "queue | diff-waiting-time | average-speed | pressure");
      v("tripinfo_output", tripinfo_output, "also write SUMO's tripinfo XML to this file");
    }
  };

  enum Approach : int { kNorth = 0, kSouth, kEast, kWest, kNumApproaches };

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
  // The light: the approach that has (or, during yellow, had) green.
  int green_approach() const { return green_; }
  bool yellow() const { return yellow_; }
  double sim_time() const { return sim_time_; }
  // A top-down picture of the roads, the vehicles (red when waiting) and the light at each
  // stop line (traffic_signal_render.cpp); 10 frames per second of video, one per decision.
  RenderSpec render_spec() const override { return {600, 600, 10.0}; }
  bool render(Frame& frame) const override;

  // The running SUMO's process id (-1 before the first reset), for tests.
  pid_t sumo_pid() const { return sumo_ ? sumo_->pid() : -1; }

  // The shipped scenario: <source dir>/sumo_data/single_intersection/single.sumocfg.
  static std::string default_scenario();

 private:
  struct Lane {
    std::string id;
    int approach = -1;  // for incoming lanes
    double length = 0, max_speed = 0, width = 3.2;
    std::vector<std::array<double, 2>> shape;  // centre line, metres
    int halting = 0, vehicles = 0;
    double mean_speed = 0;
  };
  struct VehicleRecord {
    double depart = 0;
    double waiting = 0;
  };

  void start_simulation(uint64_t sumo_seed);
  void simulate_one_second();
  void set_lights();
  void write_observation(std::span<float> obs) const;
  double reward();
  void update_info();
  [[noreturn]] void sumo_failed(const std::exception& e) const;

  Config config_;
  std::string scenario_;
  Space observation_space_;
  Space action_space_;
  Info info_;
  Rng rng_;
  bool ever_seeded_ = false;
  std::unique_ptr<SumoProcess> sumo_;
  std::string tls_;  // the traffic light's id in the scenario

  std::vector<Lane> incoming_, outgoing_;
  std::vector<int> link_approach_;    // approach of each signal link (by link index)
  double capacity_[kNumApproaches] = {};  // vehicles that fit on an approach's lanes
  int green_ = kNorth, next_green_ = kNorth;
  bool yellow_ = false;
  int since_change_ = 0;  // seconds since the last light change
  double sim_time_ = 0;
  std::map<std::string, VehicleRecord> on_road_;  // vehicles in the network
  libsumo::SubscriptionResults vehicles_;  // this second's vehicles: speed and lane
  int arrived_ = 0;
  double arrived_waiting_ = 0, arrived_travel_ = 0;
  double last_waiting_sum_ = 0;  // diff-waiting-time
  int key_waiting_, key_travel_, key_queue_, key_throughput_, key_time_;
  bool has_state_ = false;
};

}  // namespace rlrun
