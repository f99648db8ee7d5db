// backend: traci for TrafficNetwork-v0 — the network client on libtraci's classes, talking to a
// `sumo` process of its own (envs/traffic/sumo_over_traci.hpp); the libsumo backend is in the
// module (envs/traffic/libsumo_module/), loaded as for TrafficSignal-v0.
// libtraci.h first: it selects the libtraci namespace for the client headers below.
#include "rlrun/envs/traffic/sumo_over_traci.hpp"
#include "rlrun/envs/traffic_network/network_client.hpp"

namespace rlrun::traffic {

std::unique_ptr<NetworkConnection> start_network_traci(const SumoLaunch& launch) {
  return std::make_unique<SumoOverTraci<NetworkClient<TraciApi>>>(launch);
}

}  // namespace rlrun::traffic
