// backend: libsumo for TrafficNetwork-v0: the network client (traffic_network/network_client.hpp)
// on libsumo's classes, SUMO inside this process. Entered through rlrun_start_libsumo_network.
#include <libsumo/libsumo.h>

#include "rlrun/envs/traffic/libsumo_module/simulation_slot.hpp"
#include "rlrun/envs/traffic_network/network_client.hpp"

namespace rlrun::traffic {

namespace {

struct LibsumoApi {
  using Simulation = libsumo::Simulation;
  using Lane = libsumo::Lane;
  using Edge = libsumo::Edge;
  using Junction = libsumo::Junction;
  using TrafficLight = libsumo::TrafficLight;
};

class LibsumoNetwork : public NetworkClient<LibsumoApi> {
 public:
  explicit LibsumoNetwork(const std::vector<std::string>& command) {
    libsumo::Simulation::start(command);
  }
  ~LibsumoNetwork() override {
    finish();
    libsumo_module::simulation_running = false;
  }
  void finish() override {
    if (finished_) return;
    finished_ = true;
    try {
      libsumo::Simulation::close();  // writes the output files (tripinfo)
    } catch (const std::exception&) {
      // Nothing left to close.
    }
  }
  std::string output_tail() const override {
    return "  (backend: libsumo runs SUMO inside rlrun: its messages went to rlrun's own "
           "output)\n";
  }
  pid_t pid() const override { return -1; }

 private:
  bool finished_ = false;
};

}  // namespace

}  // namespace rlrun::traffic

extern "C" rlrun::traffic::NetworkConnection* rlrun_start_libsumo_network(
    const std::vector<std::string>* command, std::string* error) {
  if (rlrun::libsumo_module::simulation_running.exchange(true)) {
    *error = rlrun::libsumo_module::kOneSimulation;
    return nullptr;
  }
  try {
    return new rlrun::traffic::LibsumoNetwork(*command);
  } catch (const std::exception& e) {
    rlrun::libsumo_module::simulation_running = false;
    *error = std::string("SUMO (libsumo) did not start: ") + e.what();
    return nullptr;
  }
}
