#include "rlrun/envs/traffic_network/network_connection.hpp"

#include "rlrun/core/errors.hpp"

namespace rlrun::traffic {

std::unique_ptr<NetworkConnection> start_network_sumo(const std::string& backend,
                                                      const SumoLaunch& launch) {
  check_sumo_launch(launch);
  if (backend == "traci") return start_network_traci(launch);
  if (backend != "libsumo")
    throw RuntimeFailure("unknown SUMO backend '" + backend + "' (traci or libsumo)");
  std::vector<std::string> command{"sumo"};
  for (std::string& a : sumo_arguments(launch)) command.push_back(std::move(a));
  using Start = NetworkConnection* (*)(const std::vector<std::string>*, std::string*);
  const auto start = reinterpret_cast<Start>(libsumo_module_symbol("rlrun_start_libsumo_network"));
  std::string error;
  NetworkConnection* connection = start(&command, &error);
  if (!connection) throw RuntimeFailure(error);
  return std::unique_ptr<NetworkConnection>(connection);
}

}  // namespace rlrun::traffic
