// backend: libsumo — SUMO linked into rlrun (libsumocpp): the same TraCI calls as the traci
// backend (sumo_client.hpp) without a socket or a second process. Built as the module
// librlrun_libsumo.so (see sumo_connection.hpp for why) and entered through
// rlrun_start_libsumo_connection.
//
// SUMO holds its simulation in globals (MSNet::getInstance()), so a process runs one at a
// time; a second env asking for one gets an error that says so, rather than two envs quietly
// stepping the same simulation. sumo-rl documents the same limit for LIBSUMO_AS_TRACI.
#include <libsumo/libsumo.h>

#include "rlrun/envs/traffic/sumo_client.hpp"
#include "rlrun/envs/traffic/sumo_connection.hpp"
#include "rlrun/envs/traffic/libsumo_module/simulation_slot.hpp"

namespace rlrun {

namespace {

struct LibsumoApi {
  using Simulation = libsumo::Simulation;
  using Lane = libsumo::Lane;
  using Edge = libsumo::Edge;
  using Junction = libsumo::Junction;
  using TrafficLight = libsumo::TrafficLight;
};

using libsumo_module::simulation_running;

class LibsumoConnection : public sumo_client::ClientConnection<LibsumoApi> {
 public:
  explicit LibsumoConnection(const std::vector<std::string>& command) {
    libsumo::Simulation::start(command);
  }
  ~LibsumoConnection() override {
    finish();
    simulation_running = false;
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

}  // namespace rlrun

extern "C" rlrun::SumoConnection* rlrun_start_libsumo_connection(
    const std::vector<std::string>* command, std::string* error) {
  if (rlrun::libsumo_module::simulation_running.exchange(true)) {
    *error = rlrun::libsumo_module::kOneSimulation;
    return nullptr;
  }
  try {
    return new rlrun::LibsumoConnection(*command);
  } catch (const std::exception& e) {
    rlrun::libsumo_module::simulation_running = false;
    *error = std::string("SUMO (libsumo) did not start: ") + e.what();
    return nullptr;
  }
}
