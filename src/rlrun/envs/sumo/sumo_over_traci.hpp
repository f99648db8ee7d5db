#pragma once
// backend: traci: the client (sumo_client.hpp) on libtraci's classes, talking to a `sumo`
// process of its own (SumoProcess: pid known, output kept, no orphan). libtraci
// keeps a current connection, so each call first makes this one current.
#include <libsumo/libtraci.h>

#include <string>

#include "rlrun/envs/sumo/sumo_process.hpp"

namespace rlrun {

struct TraciApi {
  using Simulation = libtraci::Simulation;
  using Lane = libtraci::Lane;
  using Edge = libtraci::Edge;
  using Junction = libtraci::Junction;
  using TrafficLight = libtraci::TrafficLight;
  using Vehicle = libtraci::Vehicle;
  // Every read is a round trip to SUMO: subscriptions bring them all with the step's answer.
  static constexpr bool kReadsDirectly = false;
};

// `Client`: a connection class written against TraciApi's classes, with a virtual activate().
template <class Client>
class SumoOverTraci : public Client {
 public:
  explicit SumoOverTraci(const SumoLaunch& launch) : process_(launch) {}
  void finish() override { process_.stop(); }
  std::string output_tail() const override { return process_.output_tail(); }
  pid_t pid() const override { return process_.pid(); }

 protected:
  void activate() override { process_.activate(); }

 private:
  SumoProcess process_;
};

}  // namespace rlrun
