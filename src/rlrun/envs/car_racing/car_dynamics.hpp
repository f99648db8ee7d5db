#pragma once
// The car of CarRacing: gymnasium/envs/box2d/car_dynamics.py (Gymnasium 1.0.0, by Oleg Klimov,
// after Chris Campbell's top-down car tutorial, iforce2d.net/b2dtut/top-down-car) on Box2D 2.4.
// A hull of four polygons and four wheels on steering joints; each wheel spins with its own
// omega (the engine and the brakes act on it), and the difference between its rolling speed
// and its ground speed becomes a friction force, capped by the ground's grip (road tiles or
// grass). Rear-wheel drive, all-wheel brakes, front-wheel steering.
#include <array>
#include <deque>
#include <memory>
#include <optional>
#include <vector>

#include "rlrun/env/race_track_state.hpp"

class b2Body;
class b2RevoluteJoint;
class b2World;

namespace rlrun::car_racing {

// car_dynamics.py's module constants, same names (SIZE scales the drawing units to metres).
inline constexpr double kSize = 0.02;
inline constexpr double kEnginePower = 100000000 * kSize * kSize;
inline constexpr double kWheelMomentOfInertia = 4000 * kSize * kSize;
inline constexpr double kFrictionLimit = 1000000 * kSize * kSize;  // friction ~ mass ~ size^2
inline constexpr double kWheelR = 27, kWheelW = 14;                // wheel half-length, half-width
inline constexpr std::array<std::array<double, 2>, 4> kWheelPos = {
    {{-55, +80}, {+55, +80}, {-55, -82}, {+55, -82}}};  // WHEELPOS

// A skid mark (Car._create_particle): a polyline of wheel positions, drawn only in videos.
struct SkidMark {
  std::vector<std::array<double, 2>> points;
  bool grass = false;
};

class Car {
 public:
  // Creates the hull and wheels in `world` at (x, y), heading `angle` (car_dynamics.Car).
  Car(b2World& world, double angle, double x, double y);
  ~Car();  // destroys the bodies (Car.destroy)
  Car(const Car&) = delete;
  Car& operator=(const Car&) = delete;

  // The controls: gas is clipped to [0, 1] and rises at most 0.1 a step on the rear wheels;
  // brake >= 0.9 locks the wheels; steer is the front wheels' target joint angle.
  void gas(double gas);
  void brake(double brake);
  void steer(double steer);
  // Car.step(dt): steering motors, wheel spin, friction forces (before the world steps).
  void step(double dt);

  // The road tiles under each wheel, kept by the env's contact listener (wheel.tiles).
  void add_tile(int wheel, int tile) { wheels_[wheel].tiles.push_back(tile); }
  void remove_tile(int wheel, int tile);

  b2Body* hull() const { return hull_; }
  b2Body* wheel_body(int wheel) const { return wheels_[wheel].body; }
  double wheel_omega(int wheel) const { return wheels_[wheel].omega; }
  double wheel_phase(int wheel) const { return wheels_[wheel].phase; }
  double joint_angle(int wheel) const;
  CarState state() const;
  const std::deque<std::shared_ptr<SkidMark>>& skid_marks() const { return skid_marks_; }

 private:
  struct Wheel {
    b2Body* body = nullptr;
    b2RevoluteJoint* joint = nullptr;
    double gas = 0, brake = 0, steer = 0;
    double phase = 0, omega = 0;
    std::vector<int> tiles;
    std::optional<std::array<double, 2>> skid_start;
    std::shared_ptr<SkidMark> skid;
  };
  void steer_wheel(Wheel& w);
  void spin_wheel(Wheel& w, double dt);
  void track_skid(Wheel& w, bool grass);
  void end_skid(Wheel& w);

  b2World& world_;
  b2Body* hull_ = nullptr;
  std::array<Wheel, 4> wheels_;
  std::deque<std::shared_ptr<SkidMark>> skid_marks_;  // the last 30 (Car.particles)
};

}  // namespace rlrun::car_racing
