// backend: traci — the client (sumo_client.hpp) on libtraci's classes, talking to a `sumo`
// process of its own (sumo_over_traci.hpp); the libsumo backend is in the module
// (libsumo_module/).
// libtraci.h first (its own include block, so that clang-format keeps it first): it selects
// the libtraci namespace for the client header below.
#include "rlrun/envs/sumo/sumo_over_traci.hpp"

#include "rlrun/envs/sumo/sumo_client.hpp"

namespace rlrun {

std::unique_ptr<traffic::SumoConnection> start_traci_connection(const SumoLaunch& launch) {
  return std::make_unique<SumoOverTraci<traffic::SumoClient<TraciApi>>>(launch);
}

}  // namespace rlrun
