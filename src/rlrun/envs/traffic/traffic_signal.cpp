#include "rlrun/envs/traffic/traffic_signal.hpp"

#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <filesystem>
#include <stdexcept>

#include "rlrun/core/errors.hpp"
#include "rlrun/env/discrete_action.hpp"
#include "rlrun/env_seeding.hpp"
#include "rlrun/envs/traffic/tripinfo.hpp"

namespace rlrun {

namespace {

TrafficSignal::Reward parse_reward(const std::string& name) {
  if (name == "queue") return TrafficSignal::Reward::kQueue;
  if (name == "diff-waiting-time") return TrafficSignal::Reward::kDiffWaitingTime;
  if (name == "average-speed") return TrafficSignal::Reward::kAverageSpeed;
  if (name == "pressure") return TrafficSignal::Reward::kPressure;
  throw std::invalid_argument("TrafficSignal-v0: unknown reward_fn '" + name +
                              "' (queue, diff-waiting-time, average-speed or pressure)");
}

constexpr double kVehicleSpace = 5.0 + 2.5;  // length + minGap of the scenario's cars (sumo-rl)

// N, S, E or W: where an incoming lane starts, seen from the junction.
int approach_of(const SumoLaneShape& lane, double centre_x, double centre_y) {
  const double dx = lane.shape.front()[0] - centre_x, dy = lane.shape.front()[1] - centre_y;
  if (std::abs(dy) >= std::abs(dx)) return dy > 0 ? TrafficSignal::kNorth : TrafficSignal::kSouth;
  return dx > 0 ? TrafficSignal::kEast : TrafficSignal::kWest;
}

}  // namespace

TrafficSignal::TrafficSignal(const Config& config)
    : config_(config),
      reward_(parse_reward(config.reward_fn)),
      scenario_(load_traffic_scenario(config.scenario.value.empty() ? default_traffic_scenario()
                                                                    : config.scenario.value)),
      observation_space_(Space::box(0.0f, 1.0f, {10})),
      action_space_(Space::discrete(kNumApproaches)) {
  if (config_.delta_time <= config_.yellow_time)
    throw std::invalid_argument("TrafficSignal-v0: delta_time must exceed yellow_time");
  if (config_.yellow_time < 0 || config_.min_green < 0 || config_.max_green < 1 ||
      config_.num_seconds < config_.delta_time || config_.scale <= 0)
    throw std::invalid_argument(
        "TrafficSignal-v0: need yellow_time, min_green >= 0, max_green >= 1, scale > 0 and "
        "num_seconds >= delta_time");
  if (config_.backend != "traci" && config_.backend != "libsumo")
    throw std::invalid_argument("TrafficSignal-v0: unknown backend '" + config_.backend +
                                "' (traci or libsumo)");
  if (config_.gui && config_.backend == "libsumo")
    throw std::invalid_argument(
        "TrafficSignal-v0: gui: true needs backend: traci (sumo-gui is a "
        "program of its own)");
  // The episode metrics come from SUMO's tripinfo output: the user's file, else one of ours in
  // a private directory (SUMO opens the file with O_TRUNC, following links: no shared /tmp).
  if (config_.tripinfo_output.value.empty()) {
    tripinfo_dir_ =
        std::make_unique<PrivateTempDir>("rlrun-tripinfo-", PrivateTempDir::RemoveStale::kYes);
    tripinfo_path_ = tripinfo_dir_->file("tripinfo.xml");
  } else {
    tripinfo_path_ = config_.tripinfo_output.value;
  }
  key_waiting_ = info_.add_key("avg_waiting_time");
  key_travel_ = info_.add_key("avg_travel_time");
  key_queue_ = info_.add_key("total_queue_length");
  key_throughput_ = info_.add_key("throughput");
  key_time_ = info_.add_key("sim_time");
}

TrafficSignal::~TrafficSignal() {
  sumo_.reset();  // SUMO ends before its output file goes
  if (config_.tripinfo_output.value.empty()) {
    std::error_code ec;
    std::filesystem::remove(tripinfo_path_, ec);
  }
}

void TrafficSignal::sumo_failed(const std::exception& e) const {
  // A Ctrl-C while SUMO did not answer is no SUMO failure (core/worker_wait.hpp).
  if (const auto* interrupted = dynamic_cast<const Interrupted*>(&e)) throw *interrupted;
  throw RuntimeFailure("TrafficSignal-v0: SUMO stopped at simulated time " +
                       std::to_string(sim_time_) + " s (" + e.what() +
                       "); the last lines of its output:\n" +
                       (sumo_ ? sumo_->output_tail() : std::string("  (no process)\n")));
}

void TrafficSignal::start_simulation(uint64_t sumo_seed) {
  sumo_.reset();  // the previous episode's SUMO ends first
  SumoLaunch launch;
  launch.binary = config_.gui ? "sumo-gui" : config_.sumo_binary.value;
  launch.config = scenario_.sumocfg_path;
  launch.seed = sumo_seed;
  launch.scale = config_.scale * scenario_.scale;
  launch.end_time = config_.num_seconds + 1.0;
  launch.extra_args = {"--tripinfo-output", tripinfo_path_};
  sumo_ = start_sumo(config_.backend, launch);
  try {
    const SumoSignalLayout layout = sumo_->signal_layout();
    tls_ = layout.tls;
    if (incoming_.empty()) {
      // The signal's links, in SUMO's link-index order, give the lanes and their approach.
      link_approach_.assign(layout.links.size(), -1);
      const auto find = [](std::vector<Lane>& lanes, const std::string& id) {
        return std::find_if(lanes.begin(), lanes.end(), [&](const Lane& l) { return l.id == id; });
      };
      for (size_t i = 0; i < layout.links.size(); ++i) {
        for (const auto& [from, to] : layout.links[i]) {
          if (find(incoming_, from) == incoming_.end()) {
            Lane lane;
            static_cast<SumoLaneShape&>(lane) = sumo_->lane_shape(from);
            lane.approach = approach_of(lane, layout.centre_x, layout.centre_y);
            incoming_.push_back(lane);
          }
          if (find(outgoing_, to) == outgoing_.end()) {
            Lane lane;
            static_cast<SumoLaneShape&>(lane) = sumo_->lane_shape(to);
            outgoing_.push_back(lane);
          }
          link_approach_[i] = find(incoming_, from)->approach;
        }
      }
      // The roads (SUMO edges) the lanes belong to: what the subscriptions count.
      const auto add_road = [](std::vector<Road>& roads, const Lane& lane) {
        if (std::none_of(roads.begin(), roads.end(),
                         [&](const Road& r) { return r.edge == lane.edge; }))
          roads.push_back(Road{lane.edge, lane.approach, {}});
      };
      for (const Lane& lane : incoming_) {
        capacity_[lane.approach] += lane.length / kVehicleSpace;
        limit_[lane.approach] = std::max(limit_[lane.approach], lane.max_speed);
        add_road(incoming_roads_, lane);
      }
      if (reward_ == Reward::kPressure)
        for (const Lane& lane : outgoing_) add_road(outgoing_roads_, lane);
    }
    std::vector<std::string> incoming, outgoing;
    for (const Road& road : incoming_roads_) incoming.push_back(road.edge);
    for (const Road& road : outgoing_roads_) outgoing.push_back(road.edge);
    // Subscriptions: each advance's answer carries all of it.
    sumo_->subscribe(tls_, incoming, outgoing);
  } catch (const std::exception& e) {  // TraCI errors, socket errors (tcpip::SocketException)
    sumo_failed(e);
  }
}

std::string TrafficSignal::light_state(int approach, bool yellow) const {
  std::string state(link_approach_.size(), 'r');
  for (size_t i = 0; i < state.size(); ++i)
    if (link_approach_[i] == approach) state[i] = yellow ? 'y' : 'G';
  return state;
}

void TrafficSignal::advance(int seconds) {
  if (seconds <= 0) return;
  sumo_->advance(sim_time_ + seconds, state_);
  sim_time_ = state_.time;
  since_change_ += seconds;
  for (size_t i = 0; i < incoming_roads_.size(); ++i)
    incoming_roads_[i].counts = state_.incoming[i];
  for (size_t i = 0; i < outgoing_roads_.size(); ++i)
    outgoing_roads_[i].counts = state_.outgoing[i];
}

void TrafficSignal::finish_episode() {
  sumo_->finish();
  finished_ = true;
  const TripinfoSummary trips = read_tripinfo(tripinfo_path_);
  throughput_ = trips.trips;
  avg_waiting_ = trips.mean_waiting;
  avg_travel_ = trips.mean_duration;
}

void TrafficSignal::reset(std::optional<uint64_t> seed, std::span<float> obs) {
  seeding_.on_reset(seed);
  // SUMO's seed: the reset's seed as given (so `sumo --seed S` replays episode S), else the
  // env's stream.
  const uint64_t sumo_seed = seed ? *seed : seeding_.rng().next_u64();
  sim_time_ = 0;
  start_simulation(sumo_seed);
  green_ = kNorth;
  since_change_ = 0;
  state_ = SumoState{};
  vehicles_subscribed_ = false;
  finished_ = false;
  throughput_ = 0;
  avg_waiting_ = avg_travel_ = 0;
  try {
    if (needs_vehicles()) {
      sumo_->subscribe_vehicles(state_);
      vehicles_subscribed_ = true;
    }
    sumo_->set_light_state(tls_, light_state(green_, false));
    advance(1);  // subscriptions deliver their first values with a step
    since_change_ = 0;
  } catch (const std::exception& e) {  // TraCI errors, socket errors (tcpip::SocketException)
    sumo_failed(e);
  }
  last_waiting_sum_ = 0;
  has_state_ = true;
  update_info();
  write_observation(obs);
}

StepResult TrafficSignal::step(std::span<const float> action, std::span<float> obs) {
  if (!has_state_) throw std::logic_error("TrafficSignal-v0: call reset() before step()");
  if (finished_) throw std::logic_error("TrafficSignal-v0: the episode ended; call reset()");
  const int chosen = checked_discrete_action(action_space_, action, id());
  StepResult result;
  try {
    // sumo-rl TrafficSignal.set_next_phase: a different green after min_green switches
    // through yellow_time seconds of yellow (within this step); otherwise the current green
    // goes on.
    if (chosen != green_ && since_change_ >= config_.min_green) {
      sumo_->switch_light(tls_, light_state(green_, true), config_.yellow_time,
                          light_state(chosen, false));
      green_ = chosen;
      since_change_ = -config_.yellow_time;  // counts from the end of the yellow
    }
    advance(config_.delta_time);
    result.reward = reward();
    result.truncated = sim_time_ >= config_.num_seconds;
    if (result.truncated) finish_episode();
  } catch (const std::exception& e) {  // TraCI errors, socket errors (tcpip::SocketException)
    sumo_failed(e);
  }
  update_info();
  write_observation(obs);
  return result;
}

double TrafficSignal::reward() {
  if (reward_ == Reward::kQueue) {
    int halting = 0;
    for (const Road& road : incoming_roads_) halting += road.counts.halting;
    return -static_cast<double>(halting);
  }
  if (reward_ == Reward::kPressure) {
    int in = 0, out = 0;
    for (const Road& road : incoming_roads_) in += road.counts.vehicles;
    for (const Road& road : outgoing_roads_) out += road.counts.vehicles;
    return static_cast<double>(out - in);
  }
  // The vehicles on the incoming lanes (their lane comes with the context subscription);
  // sumo-rl: sum of their accumulated waiting times (SUMO's --waiting-time-memory, 100 s by
  // default), mean of speed / allowed speed.
  double waiting = 0, speed_sum = 0;
  int count = 0;
  for (const SumoVehicle& vehicle : state_.vehicles) {
    const auto lane = std::find_if(incoming_.begin(), incoming_.end(),
                                   [&](const Lane& l) { return l.id == vehicle.lane; });
    if (lane == incoming_.end()) continue;
    ++count;
    speed_sum += vehicle.speed / lane->max_speed;
    waiting += vehicle.accumulated_waiting;
  }
  if (reward_ == Reward::kAverageSpeed) return count == 0 ? 1.0 : speed_sum / count;
  // diff-waiting-time (sumo-rl): the drop of the accumulated waiting time, in 100 s.
  const double current = waiting / 100.0;
  const double r = last_waiting_sum_ - current;
  last_waiting_sum_ = current;
  return r;
}

void TrafficSignal::write_observation(std::span<float> obs) const {
  // Per approach; a road's mean speed is SUMO's vehicle-weighted mean over its lanes.
  double halting[kNumApproaches] = {}, speed_weighted[kNumApproaches] = {},
         vehicles[kNumApproaches] = {};
  for (const Road& road : incoming_roads_) {
    halting[road.approach] += road.counts.halting;
    speed_weighted[road.approach] += road.counts.mean_speed * road.counts.vehicles;
    vehicles[road.approach] += road.counts.vehicles;
  }
  for (int a = 0; a < kNumApproaches; ++a) {
    obs[a] = static_cast<float>(std::min(1.0, halting[a] / std::max(capacity_[a], 1.0)));
    obs[kNumApproaches + a] = static_cast<float>(
        vehicles[a] > 0 ? std::min(1.0, speed_weighted[a] / vehicles[a] / limit_[a]) : 1.0);
  }
  obs[8] = static_cast<float>(green_ / 3.0);
  obs[9] =
      static_cast<float>(std::min(1.0, static_cast<double>(since_change_) / config_.max_green));
}

void TrafficSignal::update_info() {
  int halting = 0;
  for (const Road& road : incoming_roads_) halting += road.counts.halting;
  info_.set(key_waiting_, avg_waiting_);
  info_.set(key_travel_, avg_travel_);
  info_.set(key_queue_, halting);
  info_.set(key_throughput_, throughput_);
  info_.set(key_time_, sim_time_);
}

}  // namespace rlrun
