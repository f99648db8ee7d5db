#include "rlrun/envs/traffic_network/traffic_network.hpp"

#include <algorithm>
#include <cmath>
#include <deque>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <stdexcept>

#include "rlrun/core/errors.hpp"
#include "rlrun/core/shipped_data.hpp"
#include "rlrun/env/action_mask.hpp"
#include "rlrun/envs/sumo/tripinfo.hpp"

namespace rlrun {

using namespace traffic;

namespace {

std::string default_scenario() {
  return (std::filesystem::path(shipped_data_dir()) / "scenarios" / "grid4x4.yaml").string();
}

// Neighbours are found within this many roads (SUMO edges) of a light: netconvert splits a road
// where lanes are added (turn lanes), so one street between two junctions is often 2-3 edges.
constexpr int kNeighbourSearchDepth = 8;

}  // namespace

const std::vector<std::string>& TrafficNetwork::network_info_keys() {
  static const std::vector<std::string> keys{"sim_time",         "total_queue_length", "mean_delay",
                                             "avg_waiting_time", "avg_travel_time",    "throughput",
                                             "mean_queue"};
  return keys;
}

TrafficNetwork::TrafficNetwork(const Config& config, std::string name,
                               const std::vector<std::string>& info_keys)
    : name_(std::move(name)),
      config_(config),
      reward_(parse_reward_function(config.reward_fn)),
      observation_(parse_observation_function(config.observation)),
      approach_phases_(config.phases == "approaches"),
      neighbourhood_(config.reward_scope == "neighbourhood"),
      scenario_(load_network_scenario(config.scenario.value.empty() ? default_scenario()
                                                                    : config.scenario.value)) {
  if (config_.backend != "traci" && config_.backend != "libsumo")
    throw std::invalid_argument(name_ + ": unknown backend '" + config_.backend +
                                "' (traci or libsumo)");
  if (config_.gui && config_.backend != "traci")
    throw std::invalid_argument(name_ +
                                ": gui: true needs backend: traci (sumo-gui is "
                                "a program of its own)");
  if (config_.reward_scope != "local" && config_.reward_scope != "neighbourhood")
    throw std::invalid_argument(name_ + ": reward_scope is local or neighbourhood");
  if (config_.delta_time <= config_.yellow_time)
    throw std::invalid_argument(name_ +
                                ": delta_time must exceed yellow_time (sumo-rl: "
                                "the yellow fits within one decision)");
  if (config_.phases != "program" && config_.phases != "approaches")
    throw std::invalid_argument(name_ + ": phases is program or approaches");
  timing_ = {config_.delta_time, config_.yellow_time, config_.min_green, config_.max_green,
             config_.max_green_switch};
  end_time_ = config_.num_seconds > 0 ? scenario_.begin + config_.num_seconds : scenario_.end;
  if (end_time_ - scenario_.begin < config_.delta_time)
    throw std::invalid_argument(name_ + ": the episode is shorter than one decision");

  // Everything from the files, before SUMO runs.
  geometry_ = read_network_geometry(scenario_.files.net);
  check_routes_fit(scenario_.files.routes, geometry_.edges, geometry_.edge_successors);
  const std::vector<TrafficLightProgram> all = read_signal_programs(scenario_.files.net);
  std::vector<TrafficLightProgram> lights = select_lights(all, config_.ts_ids, scenario_.files.net);
  if (config_.ts_ids.empty()) {
    // Every light with something to choose; a light whose program never shows green (a
    // pedestrian crossing kept red, a blinker) keeps its program.
    std::erase_if(lights, [](const TrafficLightProgram& l) {
      return std::none_of(l.phases.begin(), l.phases.end(), [](const SignalPhase& p) {
        return p.state.find('y') == std::string::npos &&
               p.state.find_first_not_of("rs") != std::string::npos;
      });
    });
    if (lights.empty())
      throw ConfigError(scenario_.files.net +
                        ": no traffic light has a green phase, so there is "
                        "no agent");
  }
  build_agents(lights);
  find_neighbours(lights);

  int most_greens = 1;
  for (const LightAgent& a : agents_) {
    most_greens = std::max(most_greens, a.num_greens());
    lane_width_ = std::max(lane_width_, a.num_incoming());
  }
  phase_width_ = most_greens;
  obs_width_ =
      (observation_ == ObservationFunction::kApproach ? kApproachObservationSize
                                                      : phase_width_ + 1 + 2 * lane_width_) +
      (config_.agent_id ? num_agents() : 0);
  observation_space_ = Space::box(0.0f, 1.0f, {obs_width_});
  action_space_ = Space::discrete(most_greens);

  work_dir_ = std::make_unique<PrivateTempDir>("rlrun-traffic-", PrivateTempDir::RemoveStale::kYes);
  tripinfo_path_ = config_.tripinfo_output.value.empty() ? work_dir_->file("tripinfo.xml")
                                                         : config_.tripinfo_output.value;
  // The info keys in `info_keys`' order; the others are not reported (-1).
  for (const std::string& key : info_keys) info_.add_key(key);
  key_time_ = info_.find("sim_time");
  key_queue_ = info_.find("total_queue_length");
  key_delay_ = info_.find("mean_delay");
  key_waiting_ = info_.find("avg_waiting_time");
  key_travel_ = info_.find("avg_travel_time");
  key_throughput_ = info_.find("throughput");
  key_mean_queue_ = info_.find("mean_queue");
  for (int k = 0; k < num_agents() * phase_width_; ++k)
    key_masks_.push_back(info_.add_key(action_mask_key(k)));
  mask_.resize(static_cast<size_t>(phase_width_));
}

TrafficNetwork::~TrafficNetwork() {
  sumo_.reset();  // SUMO ends before its files go
}

void TrafficNetwork::build_agents(const std::vector<TrafficLightProgram>& lights) {
  std::map<std::string, int> slot;
  const auto slot_of = [&](const std::string& lane) {
    const auto [it, added] = slot.emplace(lane, static_cast<int>(lanes_.size()));
    if (added) lanes_.push_back(lane);
    return it->second;
  };
  // Every incoming lane first, then the outgoing lanes that are no light's incoming lane: only
  // the pressure reward and max-pressure control need those, and SUMO evaluates a
  // subscription every simulated second, so they are subscribed only then.
  for (const TrafficLightProgram& light : lights)
    for (const std::string& lane : light.incoming_lanes) incoming_slot_[lane] = slot_of(lane);
  incoming_lanes_ = static_cast<int>(lanes_.size());
  for (const TrafficLightProgram& light : lights) {
    std::vector<int> in, out;
    std::vector<double> lengths;
    for (const std::string& lane : light.incoming_lanes) {
      in.push_back(slot_of(lane));
      lengths.push_back(geometry_.lane(lane).length);
    }
    for (const std::string& lane : light.outgoing_lanes) out.push_back(slot_of(lane));
    ApproachLayout approaches;
    if (approach_phases_ || observation_ == ObservationFunction::kApproach)
      approaches = read_approaches(light, geometry_);
    agents_.emplace_back(
        light,
        approach_phases_ ? approach_signal_control(approaches) : derive_signal_control(light),
        std::move(in), std::move(out), std::move(lengths));
    if (observation_ == ObservationFunction::kApproach) {
      std::vector<int> edge_slots;
      for (const std::string& edge : approaches.edges) {
        const auto at = std::find(edges_.begin(), edges_.end(), edge);
        edge_slots.push_back(static_cast<int>(at - edges_.begin()));
        if (at == edges_.end()) edges_.push_back(edge);
      }
      agents_.back().set_approaches(std::move(approaches), std::move(edge_slots));
    }
  }
  lane_waiting_.assign(lanes_.size(), 0.0);
  lane_speed_.assign(lanes_.size(), 0.0);
  lane_speed_count_.assign(lanes_.size(), 0);
  local_rewards_.assign(agents_.size(), 0.0);
}

void TrafficNetwork::find_neighbours(const std::vector<TrafficLightProgram>& lights) {
  const auto edge_of = [&](const std::string& lane) { return geometry_.lane(lane).edge; };
  std::map<std::string, std::set<int>> entering;  // edge -> agents it leads into
  for (size_t a = 0; a < lights.size(); ++a)
    for (const std::string& lane : lights[a].incoming_lanes)
      entering[edge_of(lane)].insert(static_cast<int>(a));
  std::vector<std::set<int>> near(lights.size());
  for (size_t a = 0; a < lights.size(); ++a) {
    std::deque<std::pair<std::string, int>> queue;
    std::set<std::string> seen;
    for (const std::string& lane : lights[a].outgoing_lanes)
      if (seen.insert(edge_of(lane)).second) queue.emplace_back(edge_of(lane), 0);
    while (!queue.empty()) {
      const auto [edge, depth] = queue.front();
      queue.pop_front();
      if (const auto it = entering.find(edge); it != entering.end()) {
        for (int b : it->second)
          if (b != static_cast<int>(a)) near[a].insert(b), near[b].insert(static_cast<int>(a));
        continue;  // traffic stops at that light
      }
      if (depth >= kNeighbourSearchDepth) continue;
      if (const auto next = geometry_.edge_successors.find(edge);
          next != geometry_.edge_successors.end())
        for (const std::string& e : next->second)
          if (seen.insert(e).second) queue.emplace_back(e, depth + 1);
    }
  }
  for (const std::set<int>& n : near) neighbours_.emplace_back(n.begin(), n.end());
}

void TrafficNetwork::sumo_failed(const std::exception& e) const {
  // A Ctrl-C while the SUMO worker did not answer is no SUMO failure (core/worker_wait.hpp).
  if (const auto* interrupted = dynamic_cast<const Interrupted*>(&e)) throw *interrupted;
  throw RuntimeFailure(name_ + ": SUMO stopped at simulated time " + std::to_string(reading_.time) +
                       " s (" + e.what() + "); the last lines of its output:\n" +
                       (sumo_ ? sumo_->output_tail() : std::string("  (no process)\n")));
}

std::string TrafficNetwork::actuated_programs_file() const {
  // SUMO's actuated control (sumo.dlr.de/docs/Simulation/Traffic_Lights.html#actuated_traffic_lights)
  // on each agent's own phases: greens between min_green and max_green seconds, extended while
  // the detectors SUMO places itself see vehicles; yellows and all-reds as in the program.
  const std::string path = work_dir_->file("actuated.add.xml");
  std::ofstream out(path);
  out << "<additional>\n";
  const std::vector<TrafficLightProgram> all = read_signal_programs(scenario_.files.net);
  for (const LightAgent& agent : agents_) {
    const auto light = std::find_if(
        all.begin(), all.end(), [&](const TrafficLightProgram& l) { return l.id == agent.id(); });
    out << "  <tlLogic id=\"" << agent.id() << "\" type=\"actuated\" programID=\"rlrun_actuated\" "
        << "offset=\"0\">\n";
    for (const SignalPhase& phase : light->phases) {
      const bool green = phase.state.find('y') == std::string::npos &&
                         phase.state.find_first_not_of("rs") != std::string::npos;
      out << "    <phase duration=\"" << phase.duration << "\" state=\"" << phase.state << "\"";
      if (green)
        out << " minDur=\"" << std::max(1, config_.min_green) << "\" maxDur=\""
            << std::max({config_.min_green, config_.max_green > 0 ? config_.max_green : 50, 1})
            << "\"";
      out << "/>\n";
    }
    out << "  </tlLogic>\n";
  }
  out << "</additional>\n";
  if (!out) throw RuntimeFailure("cannot write " + path);
  return path;
}

void TrafficNetwork::start_simulation(uint64_t seed) {
  worker_ = nullptr;
  sumo_.reset();  // the previous episode's SUMO ends first
  running_control_ = control_;
  NetworkScenario scenario = scenario_;
  scenario.end = end_time_;
  std::vector<std::string> more_additionals;
  if (running_control_ == Control::kActuated) more_additionals.push_back(actuated_programs_file());
  SumoLaunch launch;
  launch.binary = config_.gui ? "sumo-gui" : config_.sumo_binary.value;
  launch.inputs = scenario_arguments(scenario, more_additionals);
  launch.seed = seed;
  launch.scale = config_.scale * scenario_.scale;
  // sumo-rl's waiting-time memory (sumo_arguments turns XML validation off).
  launch.extra_args = {"--tripinfo-output", tripinfo_path_, "--waiting-time-memory", "1000"};
  worker_ = nullptr;
  if (config_.own_process) {
    auto worker = std::make_unique<SumoWorker>(config_.backend, launch);
    worker_ = worker.get();
    sumo_ = std::move(worker);
  } else {
    sumo_ = start_sumo(config_.backend, launch);
  }
  try {
    outgoing_subscribed_ = reward_ == RewardFunction::kPressure || watch_outgoing_;
    sumo_->subscribe(outgoing_subscribed_ ? lanes_
                                          : std::vector<std::string>(
                                                lanes_.begin(), lanes_.begin() + incoming_lanes_),
                     edges_);
    // The rewards that read vehicles need them under every control: a baseline's episodes
    // (the lights' own programs, SUMO's actuated control) get the env's reward too, so `eval
    // --baseline` compares returns, not the model's against 0 (issue 41). Subscribing only
    // reads; SUMO simulates the same either way.
    vehicles_subscribed_ = false;
    if (reward_ == RewardFunction::kDiffWaitingTime || reward_ == RewardFunction::kAverageSpeed) {
      sumo_->subscribe_vehicles(geometry_.junctions.begin()->first, reading_);
      vehicles_subscribed_ = true;
    }
    if (running_control_ == Control::kAgents)
      for (LightAgent& agent : agents_) sumo_->set_light_state(agent.id(), agent.green_state());
    if (running_control_ == Control::kActuated)
      for (LightAgent& agent : agents_) sumo_->use_program(agent.id(), "rlrun_actuated");
  } catch (const std::exception& e) {
    sumo_failed(e);
  }
}

void TrafficNetwork::advance(int seconds) {
  start_advance(seconds);
  finish_advance(seconds);
}

void TrafficNetwork::start_advance(int seconds) {
  if (worker_) worker_->start_advance(reading_.time + seconds);
}

void TrafficNetwork::finish_advance(int seconds) {
  if (worker_)
    worker_->finish_advance(reading_);
  else
    sumo_->advance(reading_.time + seconds, reading_);
  reading_.lanes.resize(lanes_.size());  // lanes not subscribed read as empty
  for (LightAgent& agent : agents_) agent.advanced(seconds);
}

void TrafficNetwork::attribute_waiting() {
  // sumo-rl's get_accumulated_waiting_time_per_lane: a vehicle's accumulated waiting time,
  // minus what was attributed to the lanes it was seen on before, counts for its current lane.
  std::fill(lane_waiting_.begin(), lane_waiting_.end(), 0.0);
  std::fill(lane_speed_.begin(), lane_speed_.end(), 0.0);
  std::fill(lane_speed_count_.begin(), lane_speed_count_.end(), 0);
  for (const VehicleReading& v : reading_.vehicles) {
    const auto slot = incoming_slot_.find(v.lane);
    if (slot == incoming_slot_.end()) continue;
    WaitingRecord& record = waiting_[v.id];
    if (record.lane != v.lane) {
      if (!record.lane.empty()) record.earlier += record.on_lane;
      record.lane = v.lane;
    }
    record.on_lane = v.accumulated_waiting - record.earlier;
    lane_waiting_[slot->second] += record.on_lane;
    if (v.allowed_speed > 0) lane_speed_[slot->second] += v.speed / v.allowed_speed;
    ++lane_speed_count_[slot->second];
  }
}

void TrafficNetwork::check_sizes(size_t obs_size, size_t actions_size) const {
  // Every agent's part, agent-major (include/rlrun/env.hpp): a caller that passes one agent's
  // buffer gets an error, not an overrun.
  const size_t agents = agents_.size();
  if (obs_size != agents * static_cast<size_t>(obs_width_) || actions_size > agents)
    throw std::invalid_argument(
        name_ + " has " + std::to_string(agents) + " agents: observations take " +
        std::to_string(agents) + " x " + std::to_string(obs_width_) + " floats (got " +
        std::to_string(obs_size) + ") and actions " + std::to_string(agents) + " (got " +
        std::to_string(actions_size) + ")");
}

void TrafficNetwork::reset(std::optional<uint64_t> seed, std::span<float> obs) {
  check_sizes(obs.size(), 0);
  seeding_.on_reset(seed);
  const uint64_t sumo_seed = seed ? *seed : seeding_.rng().next_u64();
  // phases: approaches: no yellow preceded the first green, which may end after min_green.
  const int first_green_age = approach_phases_ ? config_.yellow_time : 0;
  for (LightAgent& agent : agents_) agent.reset(first_green_age);
  reading_ = NetworkReading{};
  reading_.time = scenario_.begin;
  waiting_.clear();
  finished_ = false;
  queue_sum_ = 0;
  decisions_ = 0;
  start_simulation(sumo_seed);
  try {
    advance(1);  // subscriptions deliver their first values with a step
  } catch (const std::exception& e) {
    sumo_failed(e);
  }
  for (LightAgent& agent : agents_) agent.reset(first_green_age);  // the first green starts now
  attribute_waiting();
  for (int k : {key_delay_, key_waiting_, key_travel_, key_throughput_, key_mean_queue_})
    set_info(k, 0.0);
  has_state_ = true;
  update_info();
  write_observations(obs);
}

StepResult TrafficNetwork::step(std::span<const float> action, std::span<float> obs) {
  start_step(action);
  return finish_step(obs);
}

void TrafficNetwork::step_agents(std::span<const float> actions, std::span<float> obs,
                                 std::span<StepResult> results) {
  start_step_agents(actions);
  finish_step_agents(obs, results);
}

void TrafficNetwork::start_step(std::span<const float> action) {
  if (num_agents() != 1)
    throw std::logic_error(name_ + " has " + std::to_string(num_agents()) +
                           " agents: step them with step_agents()");
  start_step_agents(action);
}

StepResult TrafficNetwork::finish_step(std::span<float> obs) {
  StepResult result;
  finish_step_agents(obs, std::span<StepResult>(&result, 1));
  return result;
}

void TrafficNetwork::start_step_agents(std::span<const float> actions) {
  if (actions.size() != agents_.size())
    throw std::invalid_argument(name_ + ": step_agents needs one action per agent (" +
                                std::to_string(agents_.size()) + "), got " +
                                std::to_string(actions.size()));
  if (!has_state_) throw std::logic_error(name_ + ": call reset() before step()");
  if (finished_) throw std::logic_error(name_ + ": the episode ended; call reset()");
  for (size_t a = 0; a < agents_.size(); ++a) {
    const float x = actions[a];
    if (!(x >= 0 && x < static_cast<float>(action_space_.n())) || x != std::floor(x))
      throw std::invalid_argument(name_ + ": agent " + std::to_string(a) + " (" + agents_[a].id() +
                                  ") got action " + std::to_string(x) + ", not in " +
                                  action_space_.describe());
  }
  pending_seconds_ = std::max(
      1, static_cast<int>(std::min<double>(config_.delta_time, end_time_ - reading_.time)));
  try {
    if (running_control_ == Control::kAgents)
      for (size_t a = 0; a < agents_.size(); ++a) {
        const LightCommand command = agents_[a].decide(static_cast<int>(actions[a]), timing_);
        if (command.change)
          sumo_->switch_light(agents_[a].id(), command.yellow, config_.yellow_time, command.green);
      }
    start_advance(pending_seconds_);
  } catch (const std::exception& e) {
    sumo_failed(e);
  }
}

void TrafficNetwork::finish_step_agents(std::span<float> obs, std::span<StepResult> results) {
  check_sizes(obs.size(), results.size());
  if (results.size() != agents_.size())
    throw std::invalid_argument(name_ + ": step_agents needs one result per agent");
  try {
    finish_advance(pending_seconds_);
  } catch (const std::exception& e) {
    sumo_failed(e);
  }
  attribute_waiting();
  for (size_t a = 0; a < agents_.size(); ++a)
    local_rewards_[a] =
        agents_[a].reward(reward_, reading_.lanes, lane_waiting_, lane_speed_, lane_speed_count_);
  int halting = 0;
  for (const LightAgent& agent : agents_) halting += agent.queue(reading_.lanes);
  queue_sum_ += static_cast<double>(halting) / num_agents();
  ++decisions_;
  const bool truncated = reading_.time >= end_time_;
  for (size_t a = 0; a < agents_.size(); ++a) {
    double r = local_rewards_[a];
    if (neighbourhood_)
      for (int b : neighbours_[a]) r += config_.neighbour_weight * local_rewards_[b];
    results[a] = StepResult{r, false, truncated};
  }
  if (truncated) finish_episode();
  update_info();
  write_observations(obs);
}

void TrafficNetwork::finish_episode() {
  try {
    sumo_->finish();
  } catch (const std::exception& e) {
    sumo_failed(e);
  }
  finished_ = true;
  const TripinfoSummary trips = read_tripinfo(tripinfo_path_);
  set_info(key_delay_, trips.mean_time_loss);
  set_info(key_waiting_, trips.mean_waiting);
  set_info(key_travel_, trips.mean_duration);
  set_info(key_throughput_, trips.trips);
  set_info(key_mean_queue_, decisions_ > 0 ? queue_sum_ / static_cast<double>(decisions_) : 0.0);
}

void TrafficNetwork::update_info() {
  int halting = 0;
  for (const LightAgent& agent : agents_) halting += agent.queue(reading_.lanes);
  set_info(key_time_, reading_.time);
  set_info(key_queue_, halting);
  for (size_t a = 0; a < agents_.size(); ++a) {
    agents_[a].action_mask(timing_, mask_);
    for (int k = 0; k < phase_width_; ++k)
      info_.set(key_masks_[a * static_cast<size_t>(phase_width_) + k], mask_[k]);
  }
}

void TrafficNetwork::write_observations(std::span<float> obs) const {
  for (size_t a = 0; a < agents_.size(); ++a) {
    const std::span<float> row = obs.subspan(a * obs_width_, obs_width_);
    const int width = observation_ == ObservationFunction::kApproach
                          ? kApproachObservationSize
                          : phase_width_ + 1 + 2 * lane_width_;
    if (observation_ == ObservationFunction::kApproach)
      agents_[a].observe_approaches(reading_.edges, timing_, row.first(width));
    else
      agents_[a].observe(reading_.lanes, timing_, phase_width_, lane_width_, row.first(width));
    if (config_.agent_id) {
      const std::span<float> id = row.subspan(width);
      std::fill(id.begin(), id.end(), 0.0f);
      id[a] = 1.0f;
    }
  }
}

void TrafficNetwork::max_pressure_actions(std::span<float> actions) const {
  if (!has_state_) throw std::logic_error(name_ + ": call reset() before acting");
  if (!outgoing_subscribed_)
    throw std::logic_error(name_ +
                           ": max-pressure needs the outgoing lanes: call "
                           "watch_outgoing_lanes() before the episode starts");
  for (size_t a = 0; a < agents_.size(); ++a)
    actions[a] = static_cast<float>(agents_[a].max_pressure_action(reading_.lanes));
}

}  // namespace rlrun
