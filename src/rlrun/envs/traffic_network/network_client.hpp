#pragma once
// The TraCI calls TrafficNetwork-v0 makes (network_connection.hpp), written once for SUMO's two
// C++ clients: instantiated with libtraci's classes (network_traci.cpp) and libsumo's (the
// libsumo module), as envs/traffic/sumo_client.hpp does for TrafficSignal-v0. Over a socket the
// lanes and vehicles come as subscriptions with each step's answer; in-process
// (Api::kReadsDirectly) they are read after the step, which is cheaper than the subscriptions
// SUMO would evaluate at every simulated second.
#include <memory>
#include <string>
#include <vector>

#include <libsumo/TraCIConstants.h>
#include <libsumo/TraCIDefs.h>

#include "rlrun/envs/traffic/sumo_client.hpp"
#include "rlrun/envs/traffic_network/network_connection.hpp"

namespace rlrun::traffic {

// The vehicles' context subscription reaches this far (m): any city map.
constexpr double kWholeNetwork = 1e7;

template <class Api>
class NetworkClient : public NetworkConnection {
 public:
  void subscribe_lanes(const std::vector<std::string>& lanes) override {
    activate();
    lanes_ = lanes;
    if constexpr (Api::kReadsDirectly) return;
    for (const std::string& lane : lanes)
      Api::Lane::subscribe(
          lane, {libsumo::LAST_STEP_VEHICLE_NUMBER, libsumo::LAST_STEP_VEHICLE_HALTING_NUMBER,
                 libsumo::LAST_STEP_LENGTH});
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
    out.time = time;
    out.lanes.resize(lanes_.size());
    if constexpr (Api::kReadsDirectly) {
      for (size_t i = 0; i < lanes_.size(); ++i) {
        out.lanes[i].vehicles = Api::Lane::getLastStepVehicleNumber(lanes_[i]);
        out.lanes[i].halting = Api::Lane::getLastStepHaltingNumber(lanes_[i]);
        out.lanes[i].vehicle_length = Api::Lane::getLastStepLength(lanes_[i]);
      }
      if (!junction_.empty()) read_vehicles(out);
      return;
    }
    const libsumo::SubscriptionResults results = Api::Lane::getAllSubscriptionResults();
    for (size_t i = 0; i < lanes_.size(); ++i) {
      const libsumo::TraCIResults& r = results.at(lanes_[i]);
      out.lanes[i].vehicles =
          static_cast<int>(sumo_client::number(r, libsumo::LAST_STEP_VEHICLE_NUMBER));
      out.lanes[i].halting =
          static_cast<int>(sumo_client::number(r, libsumo::LAST_STEP_VEHICLE_HALTING_NUMBER));
      out.lanes[i].vehicle_length = sumo_client::number(r, libsumo::LAST_STEP_LENGTH);
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
    const libsumo::TraCILogic logic(
        "rlrun" + std::to_string(programs_++), 0, 0,
        {std::make_shared<libsumo::TraCIPhase>(yellow_seconds, yellow),
         std::make_shared<libsumo::TraCIPhase>(sumo_client::SumoClient<Api>::kForever, green)});
    Api::TrafficLight::setProgramLogic(tls, logic);
  }

  void use_program(const std::string& tls, const std::string& program_id) override {
    activate();
    Api::TrafficLight::setProgram(tls, program_id);
  }

 protected:
  virtual void activate() {}

 private:
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
      v.speed = sumo_client::number(values, libsumo::VAR_SPEED);
      v.allowed_speed = sumo_client::number(values, libsumo::VAR_ALLOWED_SPEED);
      v.accumulated_waiting = sumo_client::number(values, libsumo::VAR_ACCUMULATED_WAITING_TIME);
      v.angle = sumo_client::number(values, libsumo::VAR_ANGLE);
      const auto p =
          std::dynamic_pointer_cast<libsumo::TraCIPosition>(values.at(libsumo::VAR_POSITION));
      v.x = p->x;
      v.y = p->y;
    }
  }

  std::vector<std::string> lanes_;
  std::string junction_;
  long programs_ = 0;
};

}  // namespace rlrun::traffic
