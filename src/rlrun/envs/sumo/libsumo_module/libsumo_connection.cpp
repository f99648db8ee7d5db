// backend: libsumo — SUMO linked into rlrun (libsumocpp): the same client as the traci
// backend (sumo_client.hpp) without a socket or a second process. Built as the module
// librlrun_libsumo.so (see sumo_connection.hpp for why) and entered through
// rlrun_start_libsumo_connection, in rlrun itself (own_process: false) or in
// rlrun-sumo-worker.
#include "rlrun/envs/sumo/libsumo_module/in_process_sumo.hpp"
#include "rlrun/envs/sumo/sumo_client.hpp"
#include "rlrun/envs/sumo/sumo_connection.hpp"

using rlrun::libsumo_module::InProcessSumo;
using rlrun::libsumo_module::LibsumoApi;

extern "C" rlrun::traffic::SumoConnection* rlrun_start_libsumo_connection(
    const std::vector<std::string>* command, std::string* error) {
  return rlrun::libsumo_module::start_in_process<
      InProcessSumo<rlrun::traffic::SumoClient<LibsumoApi>>>(command, error);
}
