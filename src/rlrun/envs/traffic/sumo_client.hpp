#pragma once
// The TraCI calls TrafficSignal-v0 makes, written once for both of SUMO's C++ clients.
// libtraci (socket) and libsumo (in-process) have the same static classes — Simulation, Lane,
// Junction, TrafficLight — in two namespaces; libtraci.h selects the second by a macro, so one
// translation unit can include only one of them. Each backend's .cpp includes its header and
// instantiates SumoClient with a struct naming that namespace's classes:
//
//   struct Api { using Simulation = libtraci::Simulation; using Lane = libtraci::Lane;
//                using Edge = ...; using Junction = ...; using TrafficLight = ...; };
//
// Only libsumo's value types (TraCIDefs.h, namespace libsumo in both clients) are used here.
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include <libsumo/TraCIConstants.h>
#include <libsumo/TraCIDefs.h>

#include "rlrun/envs/traffic/sumo_connection.hpp"

namespace rlrun::sumo_client {

inline double number(const libsumo::TraCIResults& results, int variable) {
  const auto& result = results.at(variable);
  if (auto d = std::dynamic_pointer_cast<libsumo::TraCIDouble>(result)) return d->value;
  if (auto i = std::dynamic_pointer_cast<libsumo::TraCIInt>(result)) return i->value;
  throw std::runtime_error("unexpected TraCI result type for variable " + std::to_string(variable));
}

inline const std::vector<std::string>& strings(const libsumo::TraCIResults& results, int variable) {
  return std::dynamic_pointer_cast<libsumo::TraCIStringList>(results.at(variable))->value;
}

// Context subscriptions reach this far from the junction (metres): the whole network of the
// shipped scenario and of any single-intersection scenario of sensible size.
constexpr double kContextRange = 1e5;

template <class Api>
struct SumoClient {
  static SumoSignalLayout signal_layout() {
    SumoSignalLayout layout;
    layout.tls = Api::TrafficLight::getIDList().at(0);
    const libsumo::TraCIPosition centre = Api::Junction::getPosition(layout.tls);
    layout.centre_x = centre.x;
    layout.centre_y = centre.y;
    for (const auto& link_group : Api::TrafficLight::getControlledLinks(layout.tls)) {
      auto& links = layout.links.emplace_back();
      for (const libsumo::TraCILink& link : link_group)
        links.emplace_back(link.fromLane, link.toLane);
    }
    return layout;
  }

  static SumoLaneShape lane_shape(const std::string& id) {
    SumoLaneShape lane;
    lane.id = id;
    lane.edge = Api::Lane::getEdgeID(id);
    lane.length = Api::Lane::getLength(id);
    lane.max_speed = Api::Lane::getMaxSpeed(id);
    lane.width = Api::Lane::getWidth(id);
    for (const auto& p : Api::Lane::getShape(id).value) lane.shape.push_back({p.x, p.y});
    return lane;
  }

  static void subscribe(const std::vector<std::string>& incoming,
                        const std::vector<std::string>& outgoing) {
    for (const std::string& edge : incoming)
      Api::Edge::subscribe(
          edge, {libsumo::LAST_STEP_VEHICLE_HALTING_NUMBER, libsumo::LAST_STEP_MEAN_SPEED,
                 libsumo::LAST_STEP_VEHICLE_NUMBER});
    for (const std::string& edge : outgoing)
      Api::Edge::subscribe(edge, {libsumo::LAST_STEP_VEHICLE_NUMBER});
  }

  static void subscribe_vehicles(const std::string& tls) {
    Api::Junction::subscribeContext(
        tls, libsumo::CMD_GET_VEHICLE_VARIABLE, kContextRange,
        {libsumo::VAR_SPEED, libsumo::VAR_LANE_ID, libsumo::VAR_POSITION, libsumo::VAR_ANGLE,
         libsumo::VAR_ACCUMULATED_WAITING_TIME});
  }

  static void read_vehicles(const std::string& tls, SumoState& out) {
    out.vehicles.clear();
    for (const auto& [id, values] : Api::Junction::getContextSubscriptionResults(tls)) {
      SumoVehicle& v = out.vehicles.emplace_back();
      v.id = id;
      v.speed = number(values, libsumo::VAR_SPEED);
      v.angle = number(values, libsumo::VAR_ANGLE);
      v.accumulated_waiting = number(values, libsumo::VAR_ACCUMULATED_WAITING_TIME);
      v.lane =
          std::dynamic_pointer_cast<libsumo::TraCIString>(values.at(libsumo::VAR_LANE_ID))->value;
      const auto position =
          std::dynamic_pointer_cast<libsumo::TraCIPosition>(values.at(libsumo::VAR_POSITION));
      v.x = position->x;
      v.y = position->y;
    }
  }

  // `vehicles`: whether subscribe_vehicles() was called.
  static void advance(double time, const std::string& tls, const std::vector<std::string>& incoming,
                      const std::vector<std::string>& outgoing, bool vehicles, SumoState& out) {
    Api::Simulation::step(time);
    out.time = time;  // step(time) returns at `time` exactly (whole seconds, step length 1 s)
    if (vehicles) read_vehicles(tls, out);
    const libsumo::SubscriptionResults roads = Api::Edge::getAllSubscriptionResults();
    out.incoming.resize(incoming.size());
    for (size_t i = 0; i < incoming.size(); ++i) {
      const libsumo::TraCIResults& r = roads.at(incoming[i]);
      out.incoming[i].halting =
          static_cast<int>(number(r, libsumo::LAST_STEP_VEHICLE_HALTING_NUMBER));
      out.incoming[i].mean_speed = number(r, libsumo::LAST_STEP_MEAN_SPEED);
      out.incoming[i].vehicles = static_cast<int>(number(r, libsumo::LAST_STEP_VEHICLE_NUMBER));
    }
    out.outgoing.resize(outgoing.size());
    for (size_t i = 0; i < outgoing.size(); ++i)
      out.outgoing[i].vehicles =
          static_cast<int>(number(roads.at(outgoing[i]), libsumo::LAST_STEP_VEHICLE_NUMBER));
  }

  static void set_light_state(const std::string& tls, const std::string& state) {
    Api::TrafficLight::setRedYellowGreenState(tls, state);
  }

  static void switch_light(const std::string& tls, const std::string& program,
                           const std::string& yellow, int yellow_seconds,
                           const std::string& green) {
    const libsumo::TraCILogic logic(program, 0, 0,
                                    {std::make_shared<libsumo::TraCIPhase>(yellow_seconds, yellow),
                                     std::make_shared<libsumo::TraCIPhase>(kForever, green)});
    Api::TrafficLight::setProgramLogic(tls, logic);
  }
  static constexpr double kForever = 1e9;  // s: the green lasts until the next switch
};

// A SumoConnection over one of the two clients. `activate()` makes this simulation the
// client's current one (libtraci holds several connections; libsumo one simulation).
template <class Api>
class ClientConnection : public SumoConnection {
 public:
  SumoSignalLayout signal_layout() override {
    activate();
    return SumoClient<Api>::signal_layout();
  }
  SumoLaneShape lane_shape(const std::string& lane) override {
    activate();
    return SumoClient<Api>::lane_shape(lane);
  }
  void subscribe(const std::string& tls, const std::vector<std::string>& incoming,
                 const std::vector<std::string>& outgoing) override {
    tls_ = tls, incoming_ = incoming, outgoing_ = outgoing;
    activate();
    SumoClient<Api>::subscribe(incoming, outgoing);
  }
  void subscribe_vehicles(SumoState& out) override {
    activate();
    SumoClient<Api>::subscribe_vehicles(tls_);  // the answer carries the current values
    SumoClient<Api>::read_vehicles(tls_, out);
    vehicles_ = true;
  }
  void advance(double time, SumoState& out) override {
    activate();
    SumoClient<Api>::advance(time, tls_, incoming_, outgoing_, vehicles_, out);
  }
  void set_light_state(const std::string& tls, const std::string& state) override {
    activate();
    SumoClient<Api>::set_light_state(tls, state);
  }
  void switch_light(const std::string& tls, const std::string& yellow, int yellow_seconds,
                    const std::string& green) override {
    activate();
    if (yellow_seconds <= 0) return SumoClient<Api>::set_light_state(tls, green);
    SumoClient<Api>::switch_light(tls, "rlrun" + std::to_string(programs_++), yellow,
                                  yellow_seconds, green);
  }

 protected:
  virtual void activate() {}

 private:
  std::string tls_;
  std::vector<std::string> incoming_, outgoing_;
  bool vehicles_ = false;
  int programs_ = 0;
};

}  // namespace rlrun::sumo_client
