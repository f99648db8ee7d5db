#pragma once
// The TraCI calls of both traffic envs (sumo_connection.hpp), written once for SUMO's two C++
// clients. libtraci (socket) and libsumo (in-process) have the same static classes —
// Simulation, Lane, Edge, Junction, TrafficLight, Vehicle — in two namespaces; libtraci.h
// selects the second by a macro, so one translation unit can include only one of them. Each
// backend's .cpp includes its header and instantiates SumoClient with a struct naming that
// namespace's classes (TraciApi in sumo_over_traci.hpp, LibsumoApi in
// libsumo_module/in_process_sumo.hpp). Over a socket the lanes, edges and vehicles come as
// subscriptions with each step's answer; in-process (Api::kReadsDirectly) they are read after
// the step, which is cheaper than the subscriptions SUMO would evaluate at every simulated
// second. Only libsumo's value types (TraCIDefs.h, namespace libsumo in both clients) are used.
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include <libsumo/TraCIConstants.h>
#include <libsumo/TraCIDefs.h>

#include "rlrun/envs/sumo/sumo_connection.hpp"

namespace rlrun::traffic {

inline double number(const libsumo::TraCIResults& results, int variable) {
  const auto& result = results.at(variable);
  if (auto d = std::dynamic_pointer_cast<libsumo::TraCIDouble>(result)) return d->value;
  if (auto i = std::dynamic_pointer_cast<libsumo::TraCIInt>(result)) return i->value;
  throw std::runtime_error("unexpected TraCI result type for variable " + std::to_string(variable));
}

// The vehicles' context subscription reaches this far (m): any city map.
constexpr double kWholeNetwork = 1e7;

template <class Api>
class SumoClient : public SumoConnection {
 public:
  void subscribe(const std::vector<std::string>& lanes,
                 const std::vector<std::string>& edges) override {
    activate();
    lanes_ = lanes;
    edges_ = edges;
    if constexpr (Api::kReadsDirectly) return;
    for (const std::string& lane : lanes)
      Api::Lane::subscribe(
          lane, {libsumo::LAST_STEP_VEHICLE_NUMBER, libsumo::LAST_STEP_VEHICLE_HALTING_NUMBER,
                 libsumo::LAST_STEP_LENGTH});
    for (const std::string& edge : edges)
      Api::Edge::subscribe(
          edge, {libsumo::LAST_STEP_VEHICLE_HALTING_NUMBER, libsumo::LAST_STEP_MEAN_SPEED,
                 libsumo::LAST_STEP_VEHICLE_NUMBER});
  }

  void subscribe_vehicles(const std::string& junction, NetworkReading& out) override {
    activate();
    junction_ = junction;
    if constexpr (Api::kReadsDirectly) return read_vehicles(out);
    Api::Junction::subscribeContext(
        junction, libsumo::CMD_GET_VEHICLE_VARIABLE, kWholeNetwork,
        {libsumo::VAR_LANE_ID, libsumo::VAR_SPEED, libsumo::VAR_ALLOWED_SPEED,
         libsumo::VAR_ACCUMULATED_WAITING_TIME, libsumo::VAR_POSITION, libsumo::VAR_ANGLE});
    read_vehicles(out);
  }

  void advance(double time, NetworkReading& out) override {
    activate();
    Api::Simulation::step(time);
    out.time = time;  // step(time) returns at `time` exactly (whole seconds, step length 1 s)
    out.lanes.resize(lanes_.size());
    out.edges.resize(edges_.size());
    if constexpr (Api::kReadsDirectly) {
      for (size_t i = 0; i < lanes_.size(); ++i) {
        out.lanes[i].vehicles = Api::Lane::getLastStepVehicleNumber(lanes_[i]);
        out.lanes[i].halting = Api::Lane::getLastStepHaltingNumber(lanes_[i]);
        out.lanes[i].vehicle_length = Api::Lane::getLastStepLength(lanes_[i]);
      }
      for (size_t i = 0; i < edges_.size(); ++i) {
        out.edges[i].vehicles = Api::Edge::getLastStepVehicleNumber(edges_[i]);
        out.edges[i].halting = Api::Edge::getLastStepHaltingNumber(edges_[i]);
        out.edges[i].mean_speed = Api::Edge::getLastStepMeanSpeed(edges_[i]);
      }
    } else {
      read_subscribed_counts(out);
    }
    if (!junction_.empty()) read_vehicles(out);
  }

  void set_light_state(const std::string& tls, const std::string& state) override {
    activate();
    Api::TrafficLight::setRedYellowGreenState(tls, state);
  }

  void switch_light(const std::string& tls, const std::string& yellow, int yellow_seconds,
                    const std::string& green) override {
    activate();
    if (yellow_seconds <= 0) return Api::TrafficLight::setRedYellowGreenState(tls, green);
    // A new program id each time: SUMO keeps the phase timer of a program replaced under its
    // own id.
    const libsumo::TraCILogic logic("rlrun" + std::to_string(programs_++), 0, 0,
                                    {std::make_shared<libsumo::TraCIPhase>(yellow_seconds, yellow),
                                     std::make_shared<libsumo::TraCIPhase>(kForever, green)});
    Api::TrafficLight::setProgramLogic(tls, logic);
  }

  void use_program(const std::string& tls, const std::string& program_id) override {
    activate();
    Api::TrafficLight::setProgram(tls, program_id);
  }

 protected:
  virtual void activate() {}

 private:
  static constexpr double kForever = 1e9;  // s: the green lasts until the next switch

  void read_subscribed_counts(NetworkReading& out) const {
    const libsumo::SubscriptionResults lanes = Api::Lane::getAllSubscriptionResults();
    for (size_t i = 0; i < lanes_.size(); ++i) {
      const libsumo::TraCIResults& r = lanes.at(lanes_[i]);
      out.lanes[i].vehicles = static_cast<int>(number(r, libsumo::LAST_STEP_VEHICLE_NUMBER));
      out.lanes[i].halting = static_cast<int>(number(r, libsumo::LAST_STEP_VEHICLE_HALTING_NUMBER));
      out.lanes[i].vehicle_length = number(r, libsumo::LAST_STEP_LENGTH);
    }
    if (edges_.empty()) return;
    const libsumo::SubscriptionResults edges = Api::Edge::getAllSubscriptionResults();
    for (size_t i = 0; i < edges_.size(); ++i) {
      const libsumo::TraCIResults& r = edges.at(edges_[i]);
      out.edges[i].halting = static_cast<int>(number(r, libsumo::LAST_STEP_VEHICLE_HALTING_NUMBER));
      out.edges[i].mean_speed = number(r, libsumo::LAST_STEP_MEAN_SPEED);
      out.edges[i].vehicles = static_cast<int>(number(r, libsumo::LAST_STEP_VEHICLE_NUMBER));
    }
  }

  void read_vehicles(NetworkReading& out) {
    out.vehicles.clear();
    if constexpr (Api::kReadsDirectly) {
      for (const std::string& id : Api::Vehicle::getIDList()) {
        VehicleReading& v = out.vehicles.emplace_back();
        v.id = id;
        v.lane = Api::Vehicle::getLaneID(id);
        v.speed = Api::Vehicle::getSpeed(id);
        v.allowed_speed = Api::Vehicle::getAllowedSpeed(id);
        v.accumulated_waiting = Api::Vehicle::getAccumulatedWaitingTime(id);
        v.angle = Api::Vehicle::getAngle(id);
        const libsumo::TraCIPosition p = Api::Vehicle::getPosition(id, false);
        v.x = p.x;
        v.y = p.y;
      }
      return;
    }
    for (const auto& [id, values] : Api::Junction::getContextSubscriptionResults(junction_)) {
      VehicleReading& v = out.vehicles.emplace_back();
      v.id = id;
      v.lane =
          std::dynamic_pointer_cast<libsumo::TraCIString>(values.at(libsumo::VAR_LANE_ID))->value;
      v.speed = number(values, libsumo::VAR_SPEED);
      v.allowed_speed = number(values, libsumo::VAR_ALLOWED_SPEED);
      v.accumulated_waiting = number(values, libsumo::VAR_ACCUMULATED_WAITING_TIME);
      v.angle = number(values, libsumo::VAR_ANGLE);
      const auto p =
          std::dynamic_pointer_cast<libsumo::TraCIPosition>(values.at(libsumo::VAR_POSITION));
      v.x = p->x;
      v.y = p->y;
    }
  }

  std::vector<std::string> lanes_, edges_;
  std::string junction_;
  long programs_ = 0;
};

}  // namespace rlrun::traffic
