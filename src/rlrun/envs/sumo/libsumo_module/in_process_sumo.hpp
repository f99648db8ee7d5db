#pragma once
// SUMO inside this process (libsumocpp): the client (sumo_client.hpp) runs on libsumo's
// classes, and this adds what is particular to an in-process SUMO: starting and
// closing it, and the one-simulation rule.
//
// SUMO holds its simulation in globals (MSNet::getInstance()), so a process runs one at a
// time; a second env asking for one gets an error that says so, rather than two envs quietly
// stepping the same simulation. sumo-rl documents the same limit for LIBSUMO_AS_TRACI
// (own_process: true avoids it with a worker process per SUMO, sumo_worker.hpp).
#include <libsumo/libsumo.h>

#include <atomic>
#include <exception>
#include <string>
#include <vector>

namespace rlrun::libsumo_module {

struct LibsumoApi {
  using Simulation = libsumo::Simulation;
  using Lane = libsumo::Lane;
  using Edge = libsumo::Edge;
  using Junction = libsumo::Junction;
  using TrafficLight = libsumo::TrafficLight;
  using Vehicle = libsumo::Vehicle;
  // Reading a value in-process is a function call: the client reads its lanes, edges and
  // vehicles at each decision instead of subscribing (SUMO evaluates subscriptions at every
  // simulated second, most of which no one reads).
  static constexpr bool kReadsDirectly = true;
};

inline std::atomic<bool> simulation_running{false};

// `Client`: a connection class written against LibsumoApi's classes.
template <class Client>
class InProcessSumo : public Client {
 public:
  explicit InProcessSumo(const std::vector<std::string>& command) {
    libsumo::Simulation::start(command);
  }
  ~InProcessSumo() override {
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

// The module's entry: a new simulation, or nullptr with `error` saying why.
template <class Connection>
Connection* start_in_process(const std::vector<std::string>* command, std::string* error) {
  if (simulation_running.exchange(true)) {
    *error =
        "backend: libsumo runs SUMO inside rlrun, and SUMO allows one simulation per process: use "
        "n_envs: 1 and no separate eval env with libsumo (one env, one rlrun process), or "
        "backend: traci for several envs";
    return nullptr;
  }
  try {
    return new Connection(*command);
  } catch (const std::exception& e) {
    simulation_running = false;
    *error = std::string("SUMO (libsumo) did not start: ") + e.what();
    return nullptr;
  }
}

}  // namespace rlrun::libsumo_module
