// backend: traci for TrafficSignal-v0 — a `sumo` process of its own driven over its socket by
// SUMO's libtracicpp (sumo_over_traci.hpp).
// libtraci.h first (its own include block, so that clang-format keeps it first): it selects
// the libtraci namespace for the client headers below.
#include "rlrun/envs/traffic/sumo_over_traci.hpp"

#include "rlrun/envs/traffic/sumo_client.hpp"
#include "rlrun/envs/traffic/sumo_connection.hpp"

namespace rlrun {

std::unique_ptr<SumoConnection> start_traci_connection(const SumoLaunch& launch) {
  return std::make_unique<SumoOverTraci<sumo_client::ClientConnection<TraciApi>>>(launch);
}

}  // namespace rlrun
