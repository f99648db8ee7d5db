#include "rlrun/envs/traffic/traffic_signal.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <libsumo/libtraci.h>

#include "rlrun/core/errors.hpp"
#include "rlrun/env/discrete_action.hpp"
#include "rlrun/env/env_seeding.hpp"

namespace rlrun {

namespace {

constexpr double kWaitingSpeed = 0.1;       // m/s: SUMO counts a vehicle as waiting below it
constexpr double kVehicleSpace = 5.0 + 2.5;  // length + minGap of the scenario's cars (sumo-rl)

double number(const libsumo::TraCIResults& results, int variable) {
  const auto& result = results.at(variable);
  if (auto d = std::dynamic_pointer_cast<libsumo::TraCIDouble>(result)) return d->value;
  if (auto i = std::dynamic_pointer_cast<libsumo::TraCIInt>(result)) return i->value;
  throw std::runtime_error("unexpected TraCI result type for variable " + std::to_string(variable));
}

const std::vector<std::string>& strings(const libsumo::TraCIResults& results, int variable) {
  return std::dynamic_pointer_cast<libsumo::TraCIStringList>(results.at(variable))->value;
}

// N, S, E or W: where an incoming lane starts, seen from the junction.
int approach_of(const libsumo::TraCIPositionVector& shape, const libsumo::TraCIPosition& centre) {
  const double dx = shape.value.front().x - centre.x, dy = shape.value.front().y - centre.y;
  if (std::abs(dy) >= std::abs(dx)) return dy > 0 ? TrafficSignal::kNorth : TrafficSignal::kSouth;
  return dx > 0 ? TrafficSignal::kEast : TrafficSignal::kWest;
}

}  // namespace

std::string TrafficSignal::default_scenario() {
  return std::string(RLRUN_DATA_DIR) + "/sumo_data/single_intersection/single.sumocfg";
}

TrafficSignal::TrafficSignal(const Config& config)
    : config_(config),
      scenario_(config.scenario.empty() ? default_scenario() : config.scenario),
      observation_space_(Space::box(0.0f, 1.0f, {10})),
      action_space_(Space::discrete(kNumApproaches)) {
  if (config_.delta_time <= config_.yellow_time)
    throw std::invalid_argument("TrafficSignal-v0: delta_time must exceed yellow_time");
  if (config_.yellow_time < 0 || config_.min_green < 0 || config_.max_green < 1 ||
      config_.num_seconds < config_.delta_time || config_.scale <= 0)
    throw std::invalid_argument(
        "TrafficSignal-v0: need yellow_time, min_green >= 0, max_green >= 1, scale > 0 and "
        "num_seconds >= delta_time");
  if (config_.reward_fn != "queue" && config_.reward_fn != "diff-waiting-time" &&
      config_.reward_fn != "average-speed" && config_.reward_fn != "pressure")
    throw std::invalid_argument("TrafficSignal-v0: unknown reward_fn '" + config_.reward_fn +
                                "' (queue, diff-waiting-time, average-speed or pressure)");
  key_waiting_ = info_.add_key("avg_waiting_time");
  key_travel_ = info_.add_key("avg_travel_time");
  key_queue_ = info_.add_key("total_queue_length");
  key_throughput_ = info_.add_key("throughput");
  key_time_ = info_.add_key("sim_time");
}

TrafficSignal::~TrafficSignal() = default;

void TrafficSignal::sumo_failed(const std::exception& e) const {
  throw RuntimeFailure("TrafficSignal-v0: SUMO stopped at simulated time " +
                       std::to_string(sim_time_) + " s (" + e.what() +
                       "); the last lines of its output:\n" +
                       (sumo_ ? sumo_->output_tail() : std::string("  (no process)\n")));
}

void TrafficSignal::start_simulation(uint64_t sumo_seed) {
  sumo_.reset();  // the previous episode's SUMO ends first
  SumoProcess::Options options;
  options.binary = config_.gui ? "sumo-gui" : config_.sumo_binary;
  options.config = scenario_;
  options.seed = sumo_seed;
  options.scale = config_.scale;
  options.end_time = config_.num_seconds + 1.0;
  if (!config_.tripinfo_output.empty())
    options.extra_args = {"--tripinfo-output", config_.tripinfo_output};
  sumo_ = std::make_unique<SumoProcess>(options);
  sumo_->activate();
  try {
    namespace tc = libtraci;
    tls_ = tc::TrafficLight::getIDList().at(0);
    const std::string& tls = tls_;
    if (incoming_.empty()) {
      // The signal's links, in SUMO's link-index order, give the lanes and their approach.
      const libsumo::TraCIPosition centre = tc::Junction::getPosition(tls);
      const auto links = tc::TrafficLight::getControlledLinks(tls);
      link_approach_.assign(links.size(), -1);
      for (size_t i = 0; i < links.size(); ++i) {
        for (const libsumo::TraCILink& link : links[i]) {
          auto known = [](const std::vector<Lane>& lanes, const std::string& id) {
            return std::any_of(lanes.begin(), lanes.end(), [&](const Lane& l) { return l.id == id; });
          };
          if (!known(incoming_, link.fromLane)) {
            Lane lane;
            lane.id = link.fromLane;
            lane.approach = approach_of(tc::Lane::getShape(link.fromLane), centre);
            lane.length = tc::Lane::getLength(link.fromLane);
            lane.max_speed = tc::Lane::getMaxSpeed(link.fromLane);
            lane.width = tc::Lane::getWidth(link.fromLane);
            for (const auto& p : tc::Lane::getShape(link.fromLane).value) lane.shape.push_back({p.x, p.y});
            incoming_.push_back(lane);
          }
          if (!known(outgoing_, link.toLane)) {
            Lane lane;
            lane.id = link.toLane;
            lane.length = tc::Lane::getLength(link.toLane);
            lane.max_speed = tc::Lane::getMaxSpeed(link.toLane);
            lane.width = tc::Lane::getWidth(link.toLane);
            for (const auto& p : tc::Lane::getShape(link.toLane).value) lane.shape.push_back({p.x, p.y});
            outgoing_.push_back(lane);
          }
          const auto it = std::find_if(incoming_.begin(), incoming_.end(),
                                       [&](const Lane& l) { return l.id == link.fromLane; });
          link_approach_[i] = it->approach;
        }
      }
      for (const Lane& lane : incoming_) capacity_[lane.approach] += lane.length / kVehicleSpace;
    }
    // Subscriptions: every simulated second's step response carries all of it.
    for (const Lane& lane : incoming_)
      tc::Lane::subscribe(lane.id, {libsumo::LAST_STEP_VEHICLE_HALTING_NUMBER,
                                    libsumo::LAST_STEP_MEAN_SPEED,
                                    libsumo::LAST_STEP_VEHICLE_NUMBER});
    for (const Lane& lane : outgoing_)
      tc::Lane::subscribe(lane.id, {libsumo::LAST_STEP_VEHICLE_NUMBER});
    tc::Junction::subscribeContext(tls, libsumo::CMD_GET_VEHICLE_VARIABLE, 1e5,
                                   {libsumo::VAR_SPEED, libsumo::VAR_LANE_ID,
                                    libsumo::VAR_POSITION, libsumo::VAR_ANGLE});
    tc::Simulation::subscribe(std::vector<int>{libsumo::VAR_TIME, libsumo::VAR_DEPARTED_VEHICLES_IDS,
                                               libsumo::VAR_ARRIVED_VEHICLES_IDS});
  } catch (const std::exception& e) {  // TraCI errors, socket errors (tcpip::SocketException)
    sumo_failed(e);
  }
}

void TrafficSignal::set_lights() {
  std::string state(link_approach_.size(), 'r');
  for (size_t i = 0; i < state.size(); ++i)
    if (link_approach_[i] == green_) state[i] = yellow_ ? 'y' : 'G';
  libtraci::TrafficLight::setRedYellowGreenState(tls_, state);
}

void TrafficSignal::simulate_one_second() {
  namespace tc = libtraci;
  tc::Simulation::step();
  const libsumo::TraCIResults sim = tc::Simulation::getSubscriptionResults();
  sim_time_ = number(sim, libsumo::VAR_TIME);
  // Departure and arrival times as tripinfo counts them: the simulation time after the
  // step that reported them (its `duration` = arrival - depart).
  for (const std::string& id : strings(sim, libsumo::VAR_DEPARTED_VEHICLES_IDS))
    on_road_[id] = VehicleRecord{sim_time_, 0.0};
  for (const std::string& id : strings(sim, libsumo::VAR_ARRIVED_VEHICLES_IDS)) {
    const auto it = on_road_.find(id);
    if (it == on_road_.end()) continue;
    ++arrived_;
    arrived_travel_ += sim_time_ - it->second.depart;
    arrived_waiting_ += it->second.waiting;
    on_road_.erase(it);
  }
  vehicles_ = tc::Junction::getContextSubscriptionResults(tls_);
  for (const auto& [id, values] : vehicles_) {
    const auto record = on_road_.find(id);
    if (record != on_road_.end() && number(values, libsumo::VAR_SPEED) < kWaitingSpeed)
      record->second.waiting += 1.0;
  }
  const libsumo::SubscriptionResults lanes = tc::Lane::getAllSubscriptionResults();
  for (Lane& lane : incoming_) {
    const libsumo::TraCIResults& r = lanes.at(lane.id);
    lane.halting = static_cast<int>(number(r, libsumo::LAST_STEP_VEHICLE_HALTING_NUMBER));
    lane.mean_speed = number(r, libsumo::LAST_STEP_MEAN_SPEED);
    lane.vehicles = static_cast<int>(number(r, libsumo::LAST_STEP_VEHICLE_NUMBER));
  }
  for (Lane& lane : outgoing_)
    lane.vehicles = static_cast<int>(number(lanes.at(lane.id), libsumo::LAST_STEP_VEHICLE_NUMBER));
  ++since_change_;
  if (yellow_ && since_change_ >= config_.yellow_time) {
    yellow_ = false;
    green_ = next_green_;
    since_change_ = 0;
    set_lights();
  }
}

void TrafficSignal::reset(std::optional<uint64_t> seed, std::span<float> obs) {
  seed_on_reset(rng_, ever_seeded_, seed);
  // SUMO's seed: the reset's seed as given (so `sumo --seed S` replays episode S), else the
  // env's stream.
  const uint64_t sumo_seed = seed ? *seed : rng_.next_u64();
  sim_time_ = 0;
  start_simulation(sumo_seed);
  green_ = next_green_ = kNorth;
  yellow_ = false;
  since_change_ = 0;
  on_road_.clear();
  vehicles_.clear();
  arrived_ = 0;
  arrived_waiting_ = arrived_travel_ = 0;
  try {
    set_lights();
    simulate_one_second();  // subscriptions deliver their first values with a step
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
  const int chosen = checked_discrete_action(action_space_, action, id());
  StepResult result;
  try {
    sumo_->activate();
    // sumo-rl TrafficSignal.set_next_phase: a different green after min_green switches
    // through yellow; otherwise the current green goes on.
    if (chosen != green_ && since_change_ >= config_.min_green) {
      yellow_ = true;
      next_green_ = chosen;
      since_change_ = 0;
      set_lights();
    }
    for (int s = 0; s < config_.delta_time; ++s) simulate_one_second();
    result.reward = reward();
  } catch (const std::exception& e) {  // TraCI errors, socket errors (tcpip::SocketException)
    sumo_failed(e);
  }
  result.truncated = sim_time_ >= config_.num_seconds;
  update_info();
  write_observation(obs);
  return result;
}

double TrafficSignal::reward() {
  if (config_.reward_fn == "queue") {
    int halting = 0;
    for (const Lane& lane : incoming_) halting += lane.halting;
    return -static_cast<double>(halting);
  }
  if (config_.reward_fn == "pressure") {
    int in = 0, out = 0;
    for (const Lane& lane : incoming_) in += lane.vehicles;
    for (const Lane& lane : outgoing_) out += lane.vehicles;
    return static_cast<double>(out - in);
  }
  // The vehicles on the incoming lanes (their lane comes with the context subscription).
  double waiting = 0, speed_sum = 0;
  int count = 0;
  for (const auto& [id, values] : vehicles_) {
    const std::string& lane_id =
        std::dynamic_pointer_cast<libsumo::TraCIString>(values.at(libsumo::VAR_LANE_ID))->value;
    const auto lane = std::find_if(incoming_.begin(), incoming_.end(),
                                   [&](const Lane& l) { return l.id == lane_id; });
    if (lane == incoming_.end()) continue;
    ++count;
    speed_sum += number(values, libsumo::VAR_SPEED) / lane->max_speed;
    const auto record = on_road_.find(id);
    if (record != on_road_.end()) waiting += record->second.waiting;
  }
  if (config_.reward_fn == "average-speed") return count == 0 ? 1.0 : speed_sum / count;
  // diff-waiting-time (sumo-rl): the drop of the accumulated waiting time, in 100 s.
  const double current = waiting / 100.0;
  const double r = last_waiting_sum_ - current;
  last_waiting_sum_ = current;
  return r;
}

void TrafficSignal::write_observation(std::span<float> obs) const {
  double halting[kNumApproaches] = {}, speed_weighted[kNumApproaches] = {},
         vehicles[kNumApproaches] = {}, limit[kNumApproaches] = {};
  for (const Lane& lane : incoming_) {
    halting[lane.approach] += lane.halting;
    speed_weighted[lane.approach] += lane.mean_speed * lane.vehicles;
    vehicles[lane.approach] += lane.vehicles;
    limit[lane.approach] = std::max(limit[lane.approach], lane.max_speed);
  }
  for (int a = 0; a < kNumApproaches; ++a) {
    obs[a] = static_cast<float>(std::min(1.0, halting[a] / std::max(capacity_[a], 1.0)));
    obs[kNumApproaches + a] = static_cast<float>(
        vehicles[a] > 0 ? std::min(1.0, speed_weighted[a] / vehicles[a] / limit[a]) : 1.0);
  }
  obs[8] = static_cast<float>((yellow_ ? next_green_ : green_) / 3.0);
  obs[9] = static_cast<float>(std::min(1.0, static_cast<double>(since_change_) / config_.max_green));
}

void TrafficSignal::update_info() {
  int halting = 0;
  for (const Lane& lane : incoming_) halting += lane.halting;
  info_.set(key_waiting_, arrived_ > 0 ? arrived_waiting_ / arrived_ : 0.0);
  info_.set(key_travel_, arrived_ > 0 ? arrived_travel_ / arrived_ : 0.0);
  info_.set(key_queue_, halting);
  info_.set(key_throughput_, arrived_);
  info_.set(key_time_, sim_time_);
}

}  // namespace rlrun
