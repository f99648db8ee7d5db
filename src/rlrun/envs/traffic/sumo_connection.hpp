#pragma once
// What TrafficSignal-v0 needs from a running SUMO, in plain data, behind one interface with two
// backends (the issue's `backend:` key):
//
//   traci    (default) a real `sumo` process driven over a TCP socket with SUMO's own C++
//            client, libtracicpp (traci_connection.cpp, SumoProcess).
//   libsumo  the same calls into SUMO linked in-process, libsumocpp: no socket, no second
//            process (libsumo_connection.cpp). SUMO keeps a single global simulation, so one
//            per rlrun process (sumo-rl's LIBSUMO_AS_TRACI has the same limit). libsumocpp
//            pulls in ~220 shared libraries (0.1 s to load), so it lives in a module,
//            librlrun_libsumo.so, loaded the first time a libsumo env starts: every other
//            rlrun command starts as fast as before.
//
// Both backends run the same client code (sumo_client.hpp) against the libtraci or libsumo
// namespace. A decision costs one round trip (two more when the light switches: yellow, then
// green): SUMO's step(target time) runs all the decision's seconds, and subscriptions carry the
// state back with the step's answer.
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
  // Instead of `-c config --end end_time`: SUMO's input arguments as given (TrafficNetwork-v0's
  // `-n NET -r ROUTES --begin B --end E`, traffic_network/network_scenario.hpp).
  std::vector<std::string> inputs;
};

// SUMO's command line for a launch, without the program and without --remote-port.
std::vector<std::string> sumo_arguments(const SumoLaunch& launch);
// Refuses a launch whose XML inputs declare a DOCTYPE or entities (sumo_xml_guard.hpp);
// start_sumo and start_network_sumo call it before SUMO reads anything.
void check_sumo_launch(const SumoLaunch& launch);

struct SumoLaneShape {
  std::string id;
  std::string edge;  // the road (SUMO edge) the lane belongs to
  double length = 0, max_speed = 0, width = 3.2;
  std::vector<std::array<double, 2>> shape;  // centre line, metres
};

// The signal's links in SUMO's link-index order: each link's incoming and outgoing lanes.
struct SumoSignalLayout {
  std::string tls;                    // the traffic light's id (the scenario's first)
  double centre_x = 0, centre_y = 0;  // its junction's position
  std::vector<std::vector<std::pair<std::string, std::string>>> links;  // [from, to] per index
};

struct SumoVehicle {
  std::string id;
  std::string lane;
  double speed = 0, x = 0, y = 0, angle = 0;  // angle: degrees clockwise from north
  double accumulated_waiting = 0;             // s below 0.1 m/s within SUMO's --waiting-time-memory
};

struct SumoLaneCounts {
  int halting = 0, vehicles = 0;
  double mean_speed = 0;
};

// The state after an advance: subscriptions report the last simulated second of the call.
struct SumoState {
  double time = 0;
  std::vector<SumoVehicle> vehicles;               // around the junction (when subscribed)
  std::vector<SumoLaneCounts> incoming, outgoing;  // per road, in the order subscribed
};

class SumoConnection {
 public:
  virtual ~SumoConnection() = default;

  virtual SumoSignalLayout signal_layout() = 0;
  virtual SumoLaneShape lane_shape(const std::string& lane) = 0;
  // Subscribes to the roads' (SUMO edges') counts — halting, vehicles, mean speed of the
  // incoming ones, vehicles of the outgoing ones; advance() then reports them. SUMO evaluates every subscription at every simulated second, whatever the client
  // asks for (1.5 us each here: 16 lane subscriptions cost 20 % of the speed), hence roads
  // rather than lanes, and outgoing roads only for the pressure reward.
  virtual void subscribe(const std::string& tls, const std::vector<std::string>& incoming,
                         const std::vector<std::string>& outgoing) = 0;
  // Adds the vehicles within reach of the junction (id, lane, speed, position, heading,
  // accumulated waiting) to what advance() reports, and fills `out.vehicles` now. Only the
  // rewards that look at vehicles and render() need them; they cost a third of the speed.
  virtual void subscribe_vehicles(SumoState& out) = 0;
  // Runs the simulation up to `time` (SUMO's step(time): one round trip however many seconds).
  virtual void advance(double time, SumoState& out) = 0;
  virtual void set_light_state(const std::string& tls, const std::string& state) = 0;
  // `yellow` for `yellow_seconds`, then `green` until told otherwise, in one round trip: a
  // two-phase program of its own (a new program id each time: SUMO keeps the phase timer of a
  // program replaced under its own id), which SUMO switches itself within the next advance.
  virtual void switch_light(const std::string& tls, const std::string& yellow, int yellow_seconds,
                            const std::string& green) = 0;
  // Ends the simulation: SUMO completes its output files (tripinfo) and exits.
  virtual void finish() = 0;

  // For error messages: the last lines SUMO wrote (traci), or a note where they went.
  virtual std::string output_tail() const = 0;
  // The SUMO process's id, -1 for libsumo (in-process) and after finish().
  virtual pid_t pid() const = 0;
};

// Starts SUMO with `backend` "traci" or "libsumo". Throws RuntimeFailure naming the Debian
// package when `sumo` (or libsumocpp) is missing, when SUMO refuses the scenario, or when a
// second libsumo simulation is asked for in this process.
std::unique_ptr<SumoConnection> start_sumo(const std::string& backend, const SumoLaunch& launch);

// A file built and installed beside rlrun (librlrun_libsumo.so, rlrun-sumo-worker): `chosen`
// when not empty (the user's RLRUN_LIBSUMO_MODULE / RLRUN_SUMO_WORKER, core/process_settings.hpp),
// else found relative to the running binary.
std::string rlrun_helper_path(const char* name, const std::string& chosen);

// A function of the libsumo module (librlrun_libsumo.so), which is loaded on the first call.
// Throws RuntimeFailure saying what to install when it does not load.
void* libsumo_module_symbol(const char* name);

// The two backends (traci_connection.cpp; libsumo_connection.cpp via the module).
std::unique_ptr<SumoConnection> start_traci_connection(const SumoLaunch& launch);

}  // namespace rlrun

// The libsumo module's entry: starts SUMO in-process with `command` (program name first, as
// sumo_arguments() gives the rest) and returns the connection, or nullptr with `error` set.
// The module links nothing of rlrun's: everything it needs comes in through this call.
extern "C" rlrun::SumoConnection* rlrun_start_libsumo_connection(
    const std::vector<std::string>* command, std::string* error);
