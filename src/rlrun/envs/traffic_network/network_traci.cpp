// backend: traci for TrafficNetwork-v0 — a `sumo` process of its own (SumoProcess: pid known,
// output kept, no orphan) driven by SUMO's libtracicpp; the libsumo backend is in the module
// (envs/traffic/libsumo_module/), loaded as for TrafficSignal-v0.
#include <libsumo/libtraci.h>

#include "rlrun/envs/traffic/sumo_process.hpp"
#include "rlrun/envs/traffic_network/network_client.hpp"

namespace rlrun::traffic {

namespace {

struct TraciApi {
  using Simulation = libtraci::Simulation;
  using Lane = libtraci::Lane;
  using Edge = libtraci::Edge;
  using Junction = libtraci::Junction;
  using TrafficLight = libtraci::TrafficLight;
};

class TraciNetwork : public NetworkClient<TraciApi> {
 public:
  explicit TraciNetwork(const SumoLaunch& launch) : process_(launch) {}
  void finish() override { process_.stop(); }
  std::string output_tail() const override { return process_.output_tail(); }
  pid_t pid() const override { return process_.pid(); }

 protected:
  void activate() override { process_.activate(); }

 private:
  SumoProcess process_;
};

}  // namespace

std::unique_ptr<NetworkConnection> start_network_traci(const SumoLaunch& launch) {
  return std::make_unique<TraciNetwork>(launch);
}

}  // namespace rlrun::traffic
