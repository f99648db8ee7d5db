// backend: traci — a `sumo` process of its own (SumoProcess) driven over its socket by SUMO's
// libtracicpp. Several envs hold several connections; libtraci keeps a current one, so each
// call first makes this connection current.
#include <libsumo/libtraci.h>

#include "rlrun/envs/traffic/sumo_client.hpp"
#include "rlrun/envs/traffic/sumo_connection.hpp"
#include "rlrun/envs/traffic/sumo_process.hpp"

namespace rlrun {

namespace {

struct TraciApi {
  using Simulation = libtraci::Simulation;
  using Lane = libtraci::Lane;
  using Edge = libtraci::Edge;
  using Junction = libtraci::Junction;
  using TrafficLight = libtraci::TrafficLight;
};

class TraciConnection : public sumo_client::ClientConnection<TraciApi> {
 public:
  explicit TraciConnection(const SumoLaunch& launch) : process_(launch) {}

  void finish() override { process_.stop(); }
  std::string output_tail() const override { return process_.output_tail(); }
  pid_t pid() const override { return process_.pid(); }

 protected:
  void activate() override { process_.activate(); }

 private:
  SumoProcess process_;
};

}  // namespace

std::unique_ptr<SumoConnection> start_traci_connection(const SumoLaunch& launch) {
  return std::make_unique<TraciConnection>(launch);
}

}  // namespace rlrun
