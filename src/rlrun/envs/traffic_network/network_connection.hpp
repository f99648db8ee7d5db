#pragma once
// What TrafficNetwork-v0 needs from a running SUMO, in plain data: the counts of chosen lanes,
// the vehicles, and control of any light. Two backends as for TrafficSignal-v0
// (envs/traffic/sumo_connection.hpp, which also starts the processes): `traci` (a sumo process
// of its own, TCP) and `libsumo` (SUMO inside rlrun, loaded as the module librlrun_libsumo.so;
// one simulation per process). Both run the same client code (network_client.hpp).
//
// A decision costs one round trip for the step, whatever its length, plus one per light that
// switches: subscriptions bring the lanes' counts (and, when asked for, the vehicles) back with
// the step's answer.
#include <sys/types.h>

#include <memory>
#include <string>
#include <vector>

#include "rlrun/envs/traffic/sumo_connection.hpp"

namespace rlrun::traffic {

struct LaneReading {
  int vehicles = 0;           // on the lane in the last simulated second
  int halting = 0;            // of those, below 0.1 m/s
  double vehicle_length = 0;  // their mean length, m (0 when none)
};

struct VehicleReading {
  std::string id;
  std::string lane;
  double speed = 0, allowed_speed = 0, accumulated_waiting = 0;
  double x = 0, y = 0, angle = 0;  // angle: degrees clockwise from north
};

struct NetworkReading {
  double time = 0;
  std::vector<LaneReading> lanes;        // in subscribe_lanes() order
  std::vector<VehicleReading> vehicles;  // every vehicle, when subscribed
};

class NetworkConnection {
 public:
  virtual ~NetworkConnection() = default;
  // advance() then reports these lanes' counts.
  virtual void subscribe_lanes(const std::vector<std::string>& lanes) = 0;
  // advance() then also reports every vehicle in the network (a context subscription around
  // `junction` that reaches the whole map); fills `out.vehicles` now.
  virtual void subscribe_vehicles(const std::string& junction, NetworkReading& out) = 0;
  // Runs the simulation to `time` (one round trip however many seconds).
  virtual void advance(double time, NetworkReading& out) = 0;
  virtual void set_light_state(const std::string& tls, const std::string& state) = 0;
  // `yellow` for `yellow_seconds`, then `green` until told otherwise (a two-phase program that
  // SUMO switches itself within the next advance).
  virtual void switch_light(const std::string& tls, const std::string& yellow, int yellow_seconds,
                            const std::string& green) = 0;
  // Runs the light's program `program_id` (one loaded from an additional file).
  virtual void use_program(const std::string& tls, const std::string& program_id) = 0;
  // SUMO closes: output files (tripinfo) are complete.
  virtual void finish() = 0;
  virtual std::string output_tail() const = 0;
  virtual pid_t pid() const = 0;
};

// Starts SUMO with `launch.inputs` set (the scenario's -n/-r/--begin/--end). Throws
// RuntimeFailure naming the Debian package when SUMO is missing, with SUMO's last output when it
// refuses the scenario, and when a second libsumo simulation is asked for in this process.
std::unique_ptr<NetworkConnection> start_network_sumo(const std::string& backend,
                                                      const SumoLaunch& launch);
std::unique_ptr<NetworkConnection> start_network_traci(const SumoLaunch& launch);

}  // namespace rlrun::traffic

// The libsumo module's second entry (the first, rlrun_start_libsumo_connection, serves
// TrafficSignal-v0): SUMO in-process with `command` (program name first).
extern "C" rlrun::traffic::NetworkConnection* rlrun_start_libsumo_network(
    const std::vector<std::string>* command, std::string* error);
