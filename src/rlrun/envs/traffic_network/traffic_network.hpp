#pragma once
// TrafficNetwork-v0: any SUMO scenario (network_scenario.hpp), every traffic light an agent
// (light_agent.hpp has the per-light rules, sumo-rl's), one env with num_agents() agents that
// share a policy (include/rlrun/env.hpp: each agent is a column of the batch, as SuperSuit's
// pettingzoo_env_to_vec_env gives SB3, RESCO's IDQN / IPPO with parameter sharing).
//
//   agents       the lights with a green phase in their program (`ts_ids` picks some, in
//                that order); the others keep their own program.
//   spaces       Discrete(most greens of any agent); Box(phases + 1 + 2 * most incoming lanes
//                [+ agents with agent_id: true]) in [0, 1], padded with zeros (observation:
//                sumo-rl), or Box(10 [+ agents]) (observation: approach, light_agent.hpp).
//   greens       phases: program (sumo-rl's: the green phases of each light's program) or
//                approaches (one green per approach N, S, E, W, approaches.hpp; the first
//                green of an episode may end after min_green, as no yellow preceded it).
//   reward       reward_fn (light_agent.hpp): diff-waiting-time (the default of both traffic
//                envs, sumo-rl's), queue, pressure or average-speed.
//   step         `delta_time` simulated seconds for all agents at once (one TraCI round trip,
//                plus one per light that switches).
//   episode      the scenario's [begin, end] (or begin + num_seconds); all agents truncated
//                together; every reset restarts SUMO seeded (the reset's seed, else the env's
//                stream).
//   reward_scope local: each agent its own reward; neighbourhood: plus neighbour_weight times
//                its neighbours' (lights that traffic reaches from it, or it from them,
//                without passing another light; MA2C's spatially discounted reward, Chu et al.
//                2019, with one hop).
//   info         sim_time, total_queue_length (halting on the agents' incoming lanes now);
//                at the last step the episode metrics from SUMO's tripinfo output (vehicles
//                that arrived): mean_delay (mean timeLoss, RESCO's delay), avg_waiting_time,
//                avg_travel_time (duration), throughput; and mean_queue (halting vehicles per
//                agent on its incoming lanes, averaged over the decisions). Every step also
//                the agents' action masks, agent-major (action_mask.<a * greens + k>,
//                env/action_mask.hpp): the min_green rule as a mask, for MaskablePPO.
//   control      set_control(): the agents (default), the lights' own programs (the
//                fixed-time baseline: SUMO runs exactly as a plain `sumo` would) or SUMO's
//                actuated control on the agents' lights (the actuated baseline).
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <unordered_map>
#include <vector>

#include "rlrun/core/config_checks.hpp"
#include "rlrun/core/private_temp_dir.hpp"
#include "rlrun/core/trusted_values.hpp"
#include "rlrun/env.hpp"
#include "rlrun/env/agent_names.hpp"
#include "rlrun/env/split_step.hpp"
#include "rlrun/env_seeding.hpp"
#include "rlrun/envs/sumo/network_geometry.hpp"
#include "rlrun/envs/sumo/network_scenario.hpp"
#include "rlrun/envs/sumo/sumo_connection.hpp"
#include "rlrun/envs/sumo/sumo_worker.hpp"
#include "rlrun/envs/traffic_network/light_agent.hpp"
#include "rlrun/info.hpp"
#include "rlrun/space.hpp"

namespace rlrun {

class TrafficNetwork : public Env, public SplitStep, public AgentNames {
 public:
  struct Config {
    SimulatorInput scenario;  // scenarios/*.yaml or a .sumocfg
    std::string backend = "libsumo";
    bool own_process = true;
    bool gui = false;
    ProgramPath sumo_binary{"sumo"};
    double scale = 1.0;
    std::vector<std::string> ts_ids;
    int delta_time = 5;
    int yellow_time = 2;
    int min_green = 5;
    int max_green = 50;
    bool max_green_switch = true;
    int num_seconds = 0;                          // 0: the scenario's end
    std::string reward_fn = "diff-waiting-time";  // the one default (reward_function_names())
    std::string observation = "sumo-rl";
    std::string phases = "program";
    std::string reward_scope = "local";
    double neighbour_weight = 1.0;
    bool agent_id = false;
    OutputPath tripinfo_output;
    std::string render_focus;  // a light or junction id: render zooms to it
    double render_radius = 120;

    template <class V>
    void visit(V& v) {
      v("scenario", scenario,
        "scenario file (scenarios/*.yaml with net_file, route_files, begin, end) or a SUMO "
        ".sumocfg; default scenarios/grid4x4.yaml");
      v("backend", backend,
        "libsumo (SUMO inside the env's worker process: fastest) or traci (a sumo process "
        "driven over a socket; sumo_binary, gui)",
        OneOf{{"libsumo", "traci"}});
      v("own_process", own_process,
        "drive SUMO from a worker process of its own (rlrun-sumo-worker): several envs step "
        "their SUMOs in parallel, and libsumo runs one simulation per env; false: in rlrun "
        "itself (libsumo: one simulation per rlrun process)");
      v("sumo_binary", sumo_binary,
        "the sumo program to run with backend: traci (Debian package 'sumo')");
      v("gui", gui, "run sumo-gui to watch the simulation (backend: traci)");
      v("scale", scale, "demand multiplier (SUMO --scale, times the scenario's scale)",
        in_range(0.0, 1000.0).open_low());
      v("ts_ids", ts_ids, "the traffic lights that are agents (default: every light)");
      v("delta_time", delta_time, "simulated seconds per decision", in_range(1, 86400));
      v("yellow_time", yellow_time, "seconds of yellow on every switch", in_range(0, 86400));
      v("min_green", min_green, "a green lasts at least this long (seconds)", in_range(0, 86400));
      v("max_green", max_green,
        "a green this long is switched to the next green (0: never); observation: approach "
        "scales the green's age by it",
        in_range(0, 86400));
      v("max_green_switch", max_green_switch,
        "switch a green that has lasted max_green seconds (false: sumo-rl's rule, max_green "
        "only scales the approach observation)");
      v("num_seconds", num_seconds,
        "episode length in simulated seconds (0: to the scenario's end)", in_range(0, 365 * 86400));
      v("reward_fn", reward_fn,
        "diff-waiting-time (sumo-rl's, the default) | queue | pressure | average-speed",
        OneOf{traffic::reward_function_names()});
      v("observation", observation,
        "sumo-rl (green one-hot, min-green flag, lane densities and queues) or approach "
        "(Box(10): queue and speed per approach N, S, E, W, the green, its age)",
        OneOf{traffic::observation_function_names()});
      v("phases", phases,
        "program (each light's green phases, sumo-rl's) or approaches (one green per approach "
        "N, S, E, W)",
        OneOf{{"program", "approaches"}});
      v("reward_scope", reward_scope,
        "local (each light its own reward) or neighbourhood (plus neighbour_weight x its "
        "neighbours')",
        OneOf{{"local", "neighbourhood"}});
      v("neighbour_weight", neighbour_weight, "weight of the neighbours' rewards",
        in_range(0.0, 1.0));
      v("agent_id", agent_id, "append a one-hot agent index to each observation");
      v("tripinfo_output", tripinfo_output, "also write SUMO's tripinfo XML to this file");
      v("render_focus", render_focus,
        "a traffic light or junction id: video shows its surroundings (default: the whole map)");
      v("render_radius", render_radius, "metres around render_focus that the video shows",
        in_range(10.0, 1e6));
    }
  };

  enum class Control { kAgents, kOwnPrograms, kActuated };

  TrafficNetwork() : TrafficNetwork(Config{}) {}
  // Reads the scenario and the network; throws ConfigError / RuntimeFailure for bad input
  // before any SUMO runs.
  explicit TrafficNetwork(const Config& config)
      : TrafficNetwork(config, "TrafficNetwork-v0", network_info_keys()) {}
  ~TrafficNetwork() override;

  const Space& observation_space() const override { return observation_space_; }
  const Space& action_space() const override { return action_space_; }
  const Info& info() const override { return info_; }
  std::string id() const override { return name_; }
  int num_agents() const override { return static_cast<int>(agents_.size()); }
  // PettingZoo's agent names (env/agent_names.hpp): the traffic light ids, as sumo-rl's.
  std::string agent_name(int agent) const override {
    return agents_.at(static_cast<size_t>(agent)).id();
  }

  void reset(std::optional<uint64_t> seed, std::span<float> obs) override;
  StepResult step(std::span<const float> action, std::span<float> obs) override;
  void step_agents(std::span<const float> actions, std::span<float> obs,
                   std::span<StepResult> results) override;
  // The two halves (env/split_step.hpp) when SUMO runs in a worker: the decisions go out and
  // SUMO runs while other envs start theirs.
  bool steps_asynchronously() const override { return config_.own_process; }
  bool splits_agents() const override { return config_.own_process; }
  void start_step(std::span<const float> action) override;
  StepResult finish_step(std::span<float> obs) override;
  void start_step_agents(std::span<const float> actions) override;
  void finish_step_agents(std::span<float> obs, std::span<StepResult> results) override;

  RenderSpec render_spec() const override { return {800, 800, 10.0}; }
  bool render(Frame& frame) const override;

  // Takes effect at the next reset().
  void set_control(Control control) { control_ = control; }
  Control control() const { return control_; }
  // RESCO's max-pressure choice of every agent now (agent-major, as step_agents takes them).
  // It looks at the outgoing lanes too: watch_outgoing_lanes() before the episode.
  void max_pressure_actions(std::span<float> actions) const;
  void watch_outgoing_lanes() { watch_outgoing_ = true; }

  const Config& config() const { return config_; }
  const traffic::NetworkScenario& scenario() const { return scenario_; }
  const std::vector<traffic::LightAgent>& agents() const { return agents_; }
  const std::vector<std::vector<int>>& neighbours() const { return neighbours_; }
  double sim_time() const { return reading_.time; }
  pid_t sumo_pid() const { return sumo_ ? sumo_->pid() : -1; }

 protected:
  // An env registered under another `name` on the same machinery (TrafficSignal-v0), reporting
  // `info_keys` (some of network_info_keys(), in its own order).
  TrafficNetwork(const Config& config, std::string name, const std::vector<std::string>& info_keys);
  static const std::vector<std::string>& network_info_keys();

 private:
  void check_sizes(size_t obs_size, size_t actions_size) const;
  void build_agents(const std::vector<traffic::TrafficLightProgram>& lights);
  void find_neighbours(const std::vector<traffic::TrafficLightProgram>& lights);
  void start_simulation(uint64_t seed);
  std::string actuated_programs_file() const;
  void advance(int seconds);
  void start_advance(int seconds);
  void finish_advance(int seconds);
  void attribute_waiting();
  void write_observations(std::span<float> obs) const;
  void finish_episode();
  void update_info();
  void set_info(int key, double value) {
    if (key >= 0) info_.set(key, value);
  }
  [[noreturn]] void sumo_failed(const std::exception& e) const;

  std::string name_;
  Config config_;
  traffic::LightTiming timing_;
  traffic::RewardFunction reward_;
  traffic::ObservationFunction observation_;
  bool approach_phases_ = false;  // phases: approaches
  bool neighbourhood_ = false;
  traffic::NetworkScenario scenario_;
  traffic::NetworkGeometry geometry_;
  std::vector<traffic::LightAgent> agents_;
  std::vector<std::vector<int>> neighbours_;  // per agent
  std::vector<std::string> lanes_;            // every agent's incoming, then outgoing lanes
  int incoming_lanes_ = 0;                    // the first lanes_ that are incoming
  std::vector<std::string> edges_;            // the agents' incoming roads (observation: approach)
  bool watch_outgoing_ = false;               // subscribe the outgoing lanes too
  bool outgoing_subscribed_ = false;          // in the running episode
  std::unordered_map<std::string, int> incoming_slot_;  // controlled incoming lane -> slot
  int phase_width_ = 1, lane_width_ = 0, obs_width_ = 0;
  double end_time_ = 0;
  int pending_seconds_ = 0;  // the advance started by start_step_agents
  Space observation_space_, action_space_;
  Info info_;
  EnvSeeding seeding_;
  Control control_ = Control::kAgents;
  Control running_control_ = Control::kAgents;

  std::unique_ptr<traffic::SumoConnection> sumo_;
  traffic::SumoWorker* worker_ = nullptr;  // sumo_ when it is a worker (steps in two halves)
  // The last advance's news. render() may subscribe to the vehicles (it is const, like
  // Gymnasium's render(); the simulation is not changed by it).
  mutable traffic::NetworkReading reading_;
  mutable bool vehicles_subscribed_ = false;
  // diff-waiting-time (sumo-rl's get_accumulated_waiting_time_per_lane): per vehicle, its lane
  // at the last decision, the waiting time attributed to earlier lanes, and to this one.
  struct WaitingRecord {
    std::string lane;
    double earlier = 0, on_lane = 0;
  };
  std::unordered_map<std::string, WaitingRecord> waiting_;
  std::vector<double> lane_waiting_, lane_speed_;
  std::vector<int> lane_speed_count_;
  std::vector<double> local_rewards_;

  bool has_state_ = false, finished_ = false;
  double queue_sum_ = 0;
  long decisions_ = 0;
  std::string tripinfo_path_;
  std::unique_ptr<PrivateTempDir> work_dir_;  // tripinfo and actuated programs; goes with the env
  int key_time_, key_queue_, key_delay_, key_waiting_, key_travel_, key_throughput_,
      key_mean_queue_;
  std::vector<int> key_masks_;  // action_mask.<a * phase_width_ + k>
  std::vector<float> mask_;     // one agent's mask (update_info)
};

}  // namespace rlrun
