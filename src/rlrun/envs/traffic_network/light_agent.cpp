#include "rlrun/envs/traffic_network/light_agent.hpp"

#include <algorithm>
#include <stdexcept>

namespace rlrun::traffic {

namespace {

// sumo-rl's TrafficSignal.MIN_GAP: SUMO's default minimum gap between vehicles (m).
constexpr double kMinGap = 2.5;

// "a, b or c": the names a message offers, from the one list of them.
std::string alternatives(const std::vector<std::string>& names) {
  std::string text;
  for (size_t i = 0; i < names.size(); ++i)
    text += (i == 0 ? "" : i + 1 == names.size() ? " or " : ", ") + names[i];
  return text;
}

}  // namespace

const std::vector<std::string>& reward_function_names() {
  static const std::vector<std::string> names{"diff-waiting-time", "queue", "pressure",
                                              "average-speed"};
  return names;
}

RewardFunction parse_reward_function(const std::string& name) {
  const auto& names = reward_function_names();
  const auto it = std::find(names.begin(), names.end(), name);
  if (it == names.end())
    throw std::invalid_argument("unknown reward_fn '" + name + "' (" + alternatives(names) + ")");
  // In the enum's order.
  return static_cast<RewardFunction>(it - names.begin());
}

const std::vector<std::string>& observation_function_names() {
  static const std::vector<std::string> names{"sumo-rl", "approach"};
  return names;
}

ObservationFunction parse_observation_function(const std::string& name) {
  const auto& names = observation_function_names();
  const auto it = std::find(names.begin(), names.end(), name);
  if (it == names.end())
    throw std::invalid_argument("unknown observation '" + name + "' (" + alternatives(names) + ")");
  return static_cast<ObservationFunction>(it - names.begin());
}

LightAgent::LightAgent(const TrafficLightProgram& light, SignalControl control,
                       std::vector<int> in_slots, std::vector<int> out_slots,
                       std::vector<double> in_lengths)
    : id_(light.id),
      control_(std::move(control)),
      in_slots_(std::move(in_slots)),
      out_slots_(std::move(out_slots)),
      in_lengths_(std::move(in_lengths)),
      links_(light.links) {
  const auto slot_of = [](const std::vector<std::string>& lanes, const std::vector<int>& slots,
                          const std::string& lane) {
    return slots[static_cast<size_t>(std::find(lanes.begin(), lanes.end(), lane) - lanes.begin())];
  };
  for (const std::string& green : control_.green_states) {
    std::vector<std::pair<int, int>>& movements = phase_movements_.emplace_back();
    for (const SignalLink& link : light.links) {
      const size_t i = static_cast<size_t>(link.index);
      if (i >= green.size() || (green[i] != 'G' && green[i] != 'g')) continue;
      const std::pair<int, int> m{slot_of(light.incoming_lanes, in_slots_, link.from),
                                  slot_of(light.outgoing_lanes, out_slots_, link.to)};
      if (std::find(movements.begin(), movements.end(), m) == movements.end())
        movements.push_back(m);
    }
  }
}

void LightAgent::reset(int since_change) {
  green_ = 0;
  since_change_ = since_change;
  last_waiting_ = 0;
}

void LightAgent::set_approaches(ApproachLayout layout, std::vector<int> edge_slots) {
  approaches_ = std::move(layout);
  edge_slots_ = std::move(edge_slots);
}

void LightAgent::action_mask(const LightTiming& timing, std::span<float> mask) const {
  const bool may_change = since_change_ >= timing.yellow_time + timing.min_green;
  for (size_t k = 0; k < mask.size(); ++k) {
    const int green = static_cast<int>(k);
    mask[k] = green < num_greens() && (may_change || green == green_) ? 1.0f : 0.0f;
  }
}

LightCommand LightAgent::decide(int action, const LightTiming& timing) {
  LightCommand command;
  int next = action;
  const bool valid = action >= 0 && action < num_greens();
  const bool may_change = since_change_ >= timing.yellow_time + timing.min_green;
  if (!valid || next == green_ || !may_change) {
    // rlrun's max_green: a green that has run its longest goes to the program's next green.
    if (timing.max_green_switch && timing.max_green > 0 && num_greens() > 1 &&
        since_change_ - timing.yellow_time >= timing.max_green && may_change)
      next = (green_ + 1) % num_greens();
    else
      return command;
  }
  command.change = true;
  command.yellow = timing.yellow_time > 0 ? control_.yellow_states[green_][next] : std::string();
  command.green = control_.green_states[next];
  green_ = next;
  since_change_ = 0;
  return command;
}

void LightAgent::observe(const std::vector<LaneReading>& lanes, const LightTiming& timing,
                         int phase_width, int lane_width, std::span<float> obs) const {
  std::fill(obs.begin(), obs.end(), 0.0f);
  obs[green_] = 1.0f;
  obs[phase_width] = since_change_ < timing.min_green + timing.yellow_time ? 0.0f : 1.0f;
  float* density = obs.data() + phase_width + 1;
  float* queue = density + lane_width;
  for (size_t k = 0; k < in_slots_.size(); ++k) {
    const LaneReading& lane = lanes[in_slots_[k]];
    const double capacity = in_lengths_[k] / (kMinGap + lane.vehicle_length);
    density[k] = static_cast<float>(std::min(1.0, lane.vehicles / capacity));
    queue[k] = static_cast<float>(std::min(1.0, lane.halting / capacity));
  }
}

void LightAgent::observe_approaches(const std::vector<LaneReading>& edges,
                                    const LightTiming& timing, std::span<float> obs) const {
  // Per approach; a road's mean speed is SUMO's vehicle-weighted mean over its lanes.
  double halting[kNumApproaches] = {}, speed_weighted[kNumApproaches] = {},
         vehicles[kNumApproaches] = {};
  for (size_t k = 0; k < edge_slots_.size(); ++k) {
    const LaneReading& road = edges[edge_slots_[k]];
    const int a = approaches_.edge_approach[k];
    halting[a] += road.halting;
    speed_weighted[a] += road.mean_speed * road.vehicles;
    vehicles[a] += road.vehicles;
  }
  for (int a = 0; a < kNumApproaches; ++a) {
    obs[a] = static_cast<float>(std::min(1.0, halting[a] / std::max(approaches_.capacity[a], 1.0)));
    obs[kNumApproaches + a] = static_cast<float>(
        vehicles[a] > 0 ? std::min(1.0, speed_weighted[a] / vehicles[a] / approaches_.limit[a])
                        : 1.0);
  }
  obs[2 * kNumApproaches] =
      static_cast<float>(green_ / static_cast<double>(std::max(1, num_greens() - 1)));
  // Seconds of green: since the switch began, less its yellow.
  const double green_seconds = std::max(0, since_change_ - timing.yellow_time);
  obs[2 * kNumApproaches + 1] =
      static_cast<float>(std::min(1.0, green_seconds / std::max(1, timing.max_green)));
}

int LightAgent::queue(const std::vector<LaneReading>& lanes) const {
  int halting = 0;
  for (int slot : in_slots_) halting += lanes[slot].halting;
  return halting;
}

double LightAgent::reward(RewardFunction f, const std::vector<LaneReading>& lanes,
                          const std::vector<double>& lane_waiting,
                          const std::vector<double>& lane_speed,
                          const std::vector<int>& lane_speed_count) {
  switch (f) {
    case RewardFunction::kQueue: return -static_cast<double>(queue(lanes));
    case RewardFunction::kPressure: {
      // sumo-rl's get_pressure: vehicles on the outgoing lanes minus on the incoming ones.
      int in = 0, out = 0;
      for (int slot : in_slots_) in += lanes[slot].vehicles;
      for (int slot : out_slots_) out += lanes[slot].vehicles;
      return static_cast<double>(out - in);
    }
    case RewardFunction::kAverageSpeed: {
      double sum = 0;
      int count = 0;
      for (int slot : in_slots_) sum += lane_speed[slot], count += lane_speed_count[slot];
      return count == 0 ? 1.0 : sum / count;
    }
    case RewardFunction::kDiffWaitingTime: {
      double waiting = 0;
      for (int slot : in_slots_) waiting += lane_waiting[slot];
      const double current = waiting / 100.0;
      const double r = last_waiting_ - current;
      last_waiting_ = current;
      return r;
    }
  }
  return 0;
}

int LightAgent::max_pressure_action(const std::vector<LaneReading>& lanes) const {
  int best = 0;
  double best_pressure = 0;
  for (size_t p = 0; p < phase_movements_.size(); ++p) {
    double pressure = 0;
    for (const auto& [in, out] : phase_movements_[p])
      pressure += lanes[in].halting - lanes[out].halting;
    if (p == 0 || pressure > best_pressure) best = static_cast<int>(p), best_pressure = pressure;
  }
  return best;
}

}  // namespace rlrun::traffic
