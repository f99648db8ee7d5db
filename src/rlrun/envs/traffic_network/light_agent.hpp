#pragma once
// One traffic light as an agent, with sumo-rl's rules (sumo_rl/environment/traffic_signal.py,
// TrafficSignal): what an action does to the light, what the agent observes and what it is
// rewarded. The one set of per-light rules of both traffic envs (TrafficSignal-v0 is
// TrafficNetwork-v0's single-intersection case). Plain data in, decisions out: the env owns
// SUMO and calls these at each decision, so the rules can be tested without a simulation.
//
//   action       index of one of the light's greens: the green phases of its own program
//                (signal_programs.hpp, `phases: program`) or one green per approach
//                (approaches.hpp, `phases: approaches`). The current green, or any action
//                before `yellow_time + min_green` seconds have passed since the last switch
//                began, keeps the green; another green switches through its yellow state
//                (set_next_phase). An index beyond this light's greens (lights with fewer
//                greens than the widest one share the padded action space) keeps the green.
//                rlrun adds `max_green`: a green that has lasted max_green seconds is switched
//                to the next green even when the agent keeps it (sumo-rl takes max_green but
//                does not enforce it; max_green_switch: false or max_green 0 turn this off).
//   observation  `sumo-rl` (sumo-rl's default observation function): the green one-hot, 1 if
//                min_green has passed, then per incoming lane its density and its queue
//                (vehicles, halting vehicles, each / (lane length / (2.5 m + mean vehicle
//                length)), at most 1); padded with zeros to the widest light's phases and
//                lanes. `approach` (TrafficSignal-v0's, Box(10)): halting vehicles per
//                approach / its capacity (N, S, E, W), mean speed per approach / its speed
//                limit, the green / (greens - 1), seconds of green / max_green (at most 1).
//   rewards      diff-waiting-time (sumo-rl's default and both envs': drop of the waiting time
//                the vehicles on the incoming lanes have accumulated on them, / 100), queue
//                (-halting on the incoming lanes), pressure (vehicles on outgoing minus
//                incoming lanes), average-speed (mean speed / allowed speed on the incoming
//                lanes, 1 if none).
#include <span>
#include <string>
#include <vector>

#include "rlrun/envs/sumo/sumo_connection.hpp"
#include "rlrun/envs/traffic_network/approaches.hpp"
#include "rlrun/envs/traffic_network/signal_programs.hpp"

namespace rlrun::traffic {

struct LightTiming {
  int delta_time = 5;
  int yellow_time = 2;
  int min_green = 5;
  int max_green = 50;            // the approach observation's scale; the longest green
  bool max_green_switch = true;  // switch a green of max_green seconds (if max_green > 0)
};

// The reward functions by name (the `reward_fn` kwarg of both envs); the first is the default.
enum class RewardFunction { kDiffWaitingTime, kQueue, kPressure, kAverageSpeed };
const std::vector<std::string>& reward_function_names();
RewardFunction parse_reward_function(const std::string& name);  // throws std::invalid_argument

// The observation functions by name (the `observation` kwarg), as sumo-rl's observation_class.
enum class ObservationFunction { kSumoRl, kApproach };
const std::vector<std::string>& observation_function_names();
ObservationFunction parse_observation_function(const std::string& name);  // invalid_argument
constexpr int kApproachObservationSize = 2 * kNumApproaches + 2;

// What a decision does to the light.
struct LightCommand {
  bool change = false;  // false: the current green goes on
  std::string yellow;   // shown for yellow_time first (empty when yellow_time is 0)
  std::string green;
};

class LightAgent {
 public:
  // `in_slots` / `out_slots`: where the light's incoming / outgoing lanes are in the env's
  // subscribed lane list, in the order of light.incoming_lanes / outgoing_lanes.
  LightAgent(const TrafficLightProgram& light, SignalControl control, std::vector<int> in_slots,
             std::vector<int> out_slots, std::vector<double> in_lengths);

  const std::string& id() const { return id_; }
  int num_greens() const { return static_cast<int>(control_.green_states.size()); }
  int num_incoming() const { return static_cast<int>(in_slots_.size()); }
  int green() const { return green_; }
  int since_change() const { return since_change_; }
  const std::string& green_state() const { return control_.green_states[green_]; }
  const std::vector<int>& in_slots() const { return in_slots_; }
  const std::vector<int>& out_slots() const { return out_slots_; }
  const std::vector<SignalLink>& links() const { return links_; }

  // A new episode: the first green, `since_change` seconds after its switch began (0: sumo-rl's
  // rule, the first green's yellow counts as shown; yellow_time: it may end after min_green).
  void reset(int since_change = 0);
  // For the approach observation: the light's approaches and where its roads are in the env's
  // subscribed edge list (in layout.edges order).
  void set_approaches(ApproachLayout layout, std::vector<int> edge_slots);
  // sumo-rl's set_next_phase for `action` (any integer; see above).
  LightCommand decide(int action, const LightTiming& timing);
  // `seconds` of simulation passed.
  void advanced(int seconds) { since_change_ += seconds; }

  // The action mask of the next decision (env/action_mask.hpp, for MaskablePPO), one entry per
  // index of the padded action space (mask.size()): before yellow_time + min_green have passed
  // only the current green is legal (every other action would keep it anyway), afterwards each
  // of the light's greens; the padding past its own greens is never legal.
  void action_mask(const LightTiming& timing, std::span<float> mask) const;

  // Writes the observation: `phase_width` floats of one-hot, 1 flag, `lane_width` densities,
  // `lane_width` queues (obs.size() == phase_width + 1 + 2 * lane_width).
  void observe(const std::vector<LaneReading>& lanes, const LightTiming& timing, int phase_width,
               int lane_width, std::span<float> obs) const;

  // The approach observation (kApproachObservationSize floats) from the edges' counts.
  void observe_approaches(const std::vector<LaneReading>& edges, const LightTiming& timing,
                          std::span<float> obs) const;

  // The reward since the last call (diff-waiting-time keeps its previous measure).
  // `lane_waiting[slot]`: waiting time the vehicles on lane `slot` have accumulated on it;
  // `lane_speed[slot]`, `lane_speed_count[slot]`: sum of speed / allowed speed and vehicles.
  double reward(RewardFunction f, const std::vector<LaneReading>& lanes,
                const std::vector<double>& lane_waiting, const std::vector<double>& lane_speed,
                const std::vector<int>& lane_speed_count);
  // Halting vehicles on the incoming lanes.
  int queue(const std::vector<LaneReading>& lanes) const;

  // RESCO's max-pressure (resco_benchmark/agents/maxpressure.py on its mplight state): per
  // green phase, the sum over the movements it gives green (each incoming -> outgoing lane
  // pair once) of halting vehicles on the incoming lane minus on the outgoing lane; the
  // green with the largest, the first on ties.
  int max_pressure_action(const std::vector<LaneReading>& lanes) const;

 private:
  std::string id_;
  SignalControl control_;
  std::vector<int> in_slots_, out_slots_;
  std::vector<double> in_lengths_;
  std::vector<SignalLink> links_;
  std::vector<std::vector<std::pair<int, int>>> phase_movements_;  // per green: (in, out) slots
  ApproachLayout approaches_;
  std::vector<int> edge_slots_;
  int green_ = 0;
  int since_change_ = 0;  // sumo-rl's time_since_last_phase_change (from the yellow's start)
  double last_waiting_ = 0;
};

}  // namespace rlrun::traffic
