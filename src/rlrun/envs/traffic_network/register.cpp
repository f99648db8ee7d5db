// Traffic at city scale: TrafficNetwork-v0 on any SUMO scenario, with its baselines as policies
// (eval --baseline / --policy, record --policy): the network's own programs (fixed-time),
// SUMO's actuated control, and RESCO's max-pressure.
#include "rlrun/core/errors.hpp"
#include "rlrun/env/env_entry.hpp"
#include "rlrun/envs/traffic_network/traffic_network.hpp"

namespace rlrun::envs {

namespace {

TrafficNetwork& network_of(Env& env, const std::string& policy) {
  auto* network = dynamic_cast<TrafficNetwork*>(&env.unwrapped());
  if (!network)
    throw UsageError("the " + policy + " policy controls TrafficNetwork-v0's lights; this env is " +
                     env.unwrapped().id());
  return *network;
}

// A baseline that hands the lights to SUMO: the agents' actions are ignored (zeros).
PolicyFn hand_over(Env& env, const std::string& name, TrafficNetwork::Control control) {
  network_of(env, name).set_control(control);
  return [](const Eigen::MatrixXf& obs, Eigen::MatrixXf& action) { action.setZero(1, obs.cols()); };
}

}  // namespace

void register_traffic_network(EnvEntries& out) {
  EnvEntry entry = make_env_entry<TrafficNetwork>(
      "TrafficNetwork-v0",
      "any SUMO network, every traffic light an agent (sumo-rl's phases, observation and "
      "rewards), shared or per-agent policies",
      0);
  entry.policies.push_back(
      {"fixed-time", "the network's own signal programs, untouched (a plain sumo run)",
       [](Env& env, const PolicyOptions&) {
         return hand_over(env, "fixed-time", TrafficNetwork::Control::kOwnPrograms);
       }});
  entry.policies.push_back(
      {"actuated",
       "SUMO's actuated control on every agent's light (its phases, greens min_green..max_green "
       "s, extended by SUMO's own detectors)",
       [](Env& env, const PolicyOptions&) {
         return hand_over(env, "actuated", TrafficNetwork::Control::kActuated);
       }});
  entry.policies.push_back(
      {"max-pressure",
       "RESCO's max-pressure: each light the green with the largest queue difference between "
       "its incoming and outgoing lanes (min_green respected)",
       [](Env& env, const PolicyOptions&) -> PolicyFn {
         TrafficNetwork* network = &network_of(env, "max-pressure");
         network->set_control(TrafficNetwork::Control::kAgents);
         network->watch_outgoing_lanes();
         return [network](const Eigen::MatrixXf& obs, Eigen::MatrixXf& action) {
           action.resize(1, obs.cols());
           network->max_pressure_actions({action.data(), static_cast<size_t>(action.size())});
         };
       }});
  entry.metrics = {"mean_delay", "avg_waiting_time", "avg_travel_time", "throughput", "mean_queue"};
  out.push_back(std::move(entry));
}

}  // namespace rlrun::envs
