// backend: libsumo for TrafficSignal-v0 — SUMO linked into rlrun (libsumocpp): the same TraCI
// calls as the traci backend (sumo_client.hpp) without a socket or a second process. Built as
// the module librlrun_libsumo.so (see sumo_connection.hpp for why) and entered through
// rlrun_start_libsumo_connection.
#include "rlrun/envs/traffic/libsumo_module/in_process_sumo.hpp"
#include "rlrun/envs/traffic/sumo_client.hpp"
#include "rlrun/envs/traffic/sumo_connection.hpp"

using rlrun::libsumo_module::InProcessSumo;
using rlrun::libsumo_module::LibsumoApi;

extern "C" rlrun::SumoConnection* rlrun_start_libsumo_connection(
    const std::vector<std::string>* command, std::string* error) {
  return rlrun::libsumo_module::start_in_process<
      InProcessSumo<rlrun::sumo_client::ClientConnection<LibsumoApi>>>(command, error);
}
