// backend: libsumo for TrafficNetwork-v0: the network client (traffic_network/network_client.hpp)
// on libsumo's classes, SUMO inside this process (rlrun-sumo-worker's, or rlrun's with
// own_process: false). Entered through rlrun_start_libsumo_network.
#include "rlrun/envs/traffic/libsumo_module/in_process_sumo.hpp"
#include "rlrun/envs/traffic_network/network_client.hpp"

using rlrun::libsumo_module::InProcessSumo;
using rlrun::libsumo_module::LibsumoApi;

extern "C" rlrun::traffic::NetworkConnection* rlrun_start_libsumo_network(
    const std::vector<std::string>* command, std::string* error) {
  return rlrun::libsumo_module::start_in_process<
      InProcessSumo<rlrun::traffic::NetworkClient<LibsumoApi>>>(command, error);
}
