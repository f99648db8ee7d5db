#include "rlrun/envs/traffic/traffic_signal.hpp"

#include <filesystem>

#include "rlrun/core/errors.hpp"
#include "rlrun/core/shipped_data.hpp"

namespace rlrun {

TrafficNetwork::Config TrafficSignal::network_config(const Config& config) {
  TrafficNetwork::Config network;
  network.scenario = config.scenario;
  if (network.scenario.value.empty())
    network.scenario.value =
        (std::filesystem::path(shipped_data_dir()) / "scenarios" / "single_intersection.yaml")
            .string();
  network.backend = config.backend;
  network.own_process = false;
  network.gui = config.gui;
  network.sumo_binary = config.sumo_binary;
  network.scale = config.scale;
  network.delta_time = config.delta_time;
  network.yellow_time = config.yellow_time;
  network.min_green = config.min_green;
  network.max_green = config.max_green;
  network.max_green_switch = false;
  // The reset simulates the first second; num_seconds of decisions follow it.
  network.num_seconds = config.num_seconds + 1;
  network.reward_fn = config.reward_fn;
  network.observation = config.observation;
  network.phases = "approaches";
  network.tripinfo_output = config.tripinfo_output;
  return network;
}

TrafficSignal::TrafficSignal(const Config& config)
    : TrafficNetwork(
          network_config(config), "TrafficSignal-v0",
          {"avg_waiting_time", "avg_travel_time", "total_queue_length", "throughput", "sim_time"}),
      config_(config) {
  if (num_agents() != 1)
    throw ConfigError(scenario().files.net + ": TrafficSignal-v0 controls one traffic light, and " +
                      std::to_string(num_agents()) +
                      " lights here have green phases (TrafficNetwork-v0 controls them all)");
}

}  // namespace rlrun
