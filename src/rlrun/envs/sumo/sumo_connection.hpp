#pragma once
// The one SUMO backend of both traffic envs (TrafficSignal-v0 is TrafficNetwork-v0's
// single-intersection case): what the envs need from a running SUMO, in plain data — the counts
// of chosen lanes and edges, the vehicles, control of any light — behind one interface with two
// backends (the `backend:` key):
//
//   traci    a real `sumo` process driven over a TCP socket with SUMO's own C++ client,
//            libtracicpp (traci_connection.cpp, SumoProcess).
//   libsumo  the same calls into SUMO linked in-process, libsumocpp: no socket, no second
//            process (libsumo_module/). SUMO keeps a single global simulation, so one per
//            process (sumo-rl's LIBSUMO_AS_TRACI has the same limit; sumo_worker.hpp runs each
//            in a worker process of its own). libsumocpp pulls in ~220 shared libraries (0.1 s
//            to load), so it lives in a module, librlrun_libsumo.so, loaded the first time a
//            libsumo simulation starts: every other rlrun command starts as fast as before.
//
// Both backends run the same client code (sumo_client.hpp) against the libtraci or libsumo
// namespace. A decision costs one round trip for the step, whatever its length (SUMO's
// step(target time)), plus one per light that switches; subscriptions carry the state back
// with the step's answer.
//
// This folder (envs/sumo/) is the backend: processes, connections, the worker, scenario and
// network files, tripinfo. It includes nothing of the envs built on it.
#include <sys/types.h>

#include <array>
#include <cstdint>
#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace rlrun {

struct SumoLaunch {
  std::string binary = "sumo";  // `sumo-gui` for gui: true (traci only)
  std::string config;           // the .sumocfg file
  uint64_t seed = 0;
  double scale = 1.0;                   // demand multiplier (SUMO --scale)
  double end_time = 3600.0;             // simulated seconds (SUMO --end)
  std::vector<std::string> extra_args;  // e.g. --tripinfo-output FILE
  // Instead of `-c config --end end_time`: SUMO's input arguments as given (a scenario's
  // `-n NET -r ROUTES --begin B --end E` or `-c CFG --begin B --end E`, network_scenario.hpp).
  std::vector<std::string> inputs;
};

// SUMO's command line for a launch, without the program and without --remote-port.
std::vector<std::string> sumo_arguments(const SumoLaunch& launch);
// Refuses a launch whose XML inputs declare a DOCTYPE or entities (sumo_xml_guard.hpp);
// start_sumo and the worker call it before SUMO reads anything.
void check_sumo_launch(const SumoLaunch& launch);

namespace traffic {

// A lane's or an edge's counts in the last simulated second.
struct LaneReading {
  int vehicles = 0;           // on the lane (edge)
  int halting = 0;            // of those, below 0.1 m/s
  double vehicle_length = 0;  // lanes: their mean length, m (0 when none)
  double mean_speed = 0;      // edges: SUMO's mean speed on the edge, m/s
};

struct VehicleReading {
  std::string id;
  std::string lane;
  double speed = 0, allowed_speed = 0, accumulated_waiting = 0;
  double x = 0, y = 0, angle = 0;  // angle: degrees clockwise from north
};

struct NetworkReading {
  double time = 0;
  std::vector<LaneReading> lanes;        // in subscribe() order
  std::vector<LaneReading> edges;        // in subscribe() order
  std::vector<VehicleReading> vehicles;  // every vehicle, when subscribed
};

class SumoConnection {
 public:
  virtual ~SumoConnection() = default;
  // advance() then reports these lanes' counts (vehicles, halting, vehicle length) and these
  // edges' (vehicles, halting, mean speed). SUMO evaluates a subscription at every simulated
  // second whoever reads it (1.5 us each): subscribe only what the rules read.
  virtual void subscribe(const std::vector<std::string>& lanes,
                         const std::vector<std::string>& edges) = 0;
  // advance() then also reports every vehicle in the network (a context subscription around
  // `junction` that reaches the whole map); fills `out.vehicles` now.
  virtual void subscribe_vehicles(const std::string& junction, NetworkReading& out) = 0;
  // Runs the simulation to `time` (SUMO's step(time): one round trip however many seconds).
  virtual void advance(double time, NetworkReading& out) = 0;
  virtual void set_light_state(const std::string& tls, const std::string& state) = 0;
  // `yellow` for `yellow_seconds`, then `green` until told otherwise, in one round trip: a
  // two-phase program of its own (a new program id each time: SUMO keeps the phase timer of a
  // program replaced under its own id), which SUMO switches itself within the next advance.
  virtual void switch_light(const std::string& tls, const std::string& yellow, int yellow_seconds,
                            const std::string& green) = 0;
  // Runs the light's program `program_id` (one loaded from an additional file).
  virtual void use_program(const std::string& tls, const std::string& program_id) = 0;
  // Ends the simulation: SUMO completes its output files (tripinfo) and exits.
  virtual void finish() = 0;

  // For error messages: the last lines SUMO wrote (traci), or a note where they went.
  virtual std::string output_tail() const = 0;
  // The SUMO process's id, -1 for libsumo (in-process) and after finish().
  virtual pid_t pid() const = 0;
};

}  // namespace traffic

// Starts SUMO with `backend` "traci" or "libsumo". Throws RuntimeFailure naming the Debian
// package when `sumo` (or libsumocpp) is missing, when SUMO refuses the scenario, or when a
// second libsumo simulation is asked for in this process.
std::unique_ptr<traffic::SumoConnection> start_sumo(const std::string& backend,
                                                    const SumoLaunch& launch);

// A file built and installed beside rlrun (librlrun_libsumo.so, rlrun-sumo-worker): `chosen`
// when not empty (the user's RLRUN_LIBSUMO_MODULE / RLRUN_SUMO_WORKER, core/process_settings.hpp),
// else found relative to the running binary.
std::string rlrun_helper_path(const char* name, const std::string& chosen);

// A function of the libsumo module (librlrun_libsumo.so), which is loaded on the first call.
// Throws RuntimeFailure saying what to install when it does not load.
void* libsumo_module_symbol(const char* name);

// The two backends (traci_connection.cpp; libsumo_connection.cpp via the module).
std::unique_ptr<traffic::SumoConnection> start_traci_connection(const SumoLaunch& launch);

}  // namespace rlrun

// The libsumo module's entry: starts SUMO in-process with `command` (program name first, as
// sumo_arguments() gives the rest) and returns the connection, or nullptr with `error` set.
// The module links nothing of rlrun's: everything it needs comes in through this call.
extern "C" rlrun::traffic::SumoConnection* rlrun_start_libsumo_connection(
    const std::vector<std::string>* command, std::string* error);
