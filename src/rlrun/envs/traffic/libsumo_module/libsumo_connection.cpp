// backend: libsumo — SUMO linked into rlrun (libsumocpp): the same TraCI calls as the traci
// backend (sumo_client.hpp) without a socket or a second process. Built as the module
// librlrun_libsumo.so (see sumo_connection.hpp for why) and entered through
// rlrun_start_libsumo_connection.
//
// SUMO holds its simulation in globals (MSNet::getInstance()), so a process runs one at a
// time; a second env asking for one gets an error that says so, rather than two envs quietly
// stepping the same simulation. sumo-rl documents the same limit for LIBSUMO_AS_TRACI.
#include <atomic>

#include <libsumo/libsumo.h>

#include "rlrun/envs/traffic/sumo_client.hpp"
#include "rlrun/envs/traffic/sumo_connection.hpp"

namespace rlrun {

namespace {

struct LibsumoApi {
  using Simulation = libsumo::Simulation;
  using Lane = libsumo::Lane;
  using Edge = libsumo::Edge;
  using Junction = libsumo::Junction;
  using TrafficLight = libsumo::TrafficLight;
};

std::atomic<bool> simulation_running{false};

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
  if (rlrun::simulation_running.exchange(true)) {
    *error =
        "backend: libsumo runs SUMO inside rlrun, and SUMO allows one simulation per process: "
        "use n_envs: 1 with libsumo (one env, one rlrun process), or backend: traci for "
        "several envs";
    return nullptr;
  }
  try {
    return new rlrun::LibsumoConnection(*command);
  } catch (const std::exception& e) {
    rlrun::simulation_running = false;
    *error = std::string("SUMO (libsumo) did not start: ") + e.what();
    return nullptr;
  }
}
