#include "rlrun/envs/car_racing/car_dynamics.hpp"
#include "rlrun/envs/car_racing/race_track.hpp"

#include <box2d/box2d.h>

#include <algorithm>
#include <cmath>

namespace rlrun::car_racing {

namespace {

// The hull's four convex parts (HULL_POLY1..4), in car_dynamics.py's drawing units.
const std::vector<std::vector<std::array<double, 2>>> kHullPolys = {
    {{-60, +130}, {+60, +130}, {+60, +110}, {-60, +110}},
    {{-15, +120}, {+15, +120}, {+20, +20}, {-20, 20}},
    {{+25, +20},
     {+50, -10},
     {+50, -40},
     {+20, -90},
     {-20, -90},
     {-50, -40},
     {-50, -10},
     {-25, +20}},
    {{-50, -120}, {+50, -120}, {+50, -90}, {-50, -90}},
};
constexpr double kWheelRad = kWheelR * kSize;  // w.wheel_rad (front_k is 1 for every wheel)
// "Random coefficient to cut oscillations in few steps (have no effect on friction_limit)".
constexpr double kForceCoefficient = 205000 * kSize * kSize;
constexpr double kBrakeForce = 15;  // BRAKE_FORCE, radians per second
constexpr size_t kMaxSkidMarks = 30, kMaxSkidPoints = 30;

b2PolygonShape polygon(const std::vector<std::array<double, 2>>& points) {
  std::vector<b2Vec2> vertices;
  for (const auto& [x, y] : points)
    vertices.emplace_back(static_cast<float>(x * kSize), static_cast<float>(y * kSize));
  b2PolygonShape shape;
  shape.Set(vertices.data(), static_cast<int32>(vertices.size()));
  return shape;
}

RigidBodyState body_state(const b2Body* body) {
  RigidBodyState s;
  s.position = {body->GetPosition().x, body->GetPosition().y};
  s.linear_velocity = {body->GetLinearVelocity().x, body->GetLinearVelocity().y};
  s.angle = body->GetAngle();
  s.angular_velocity = body->GetAngularVelocity();
  return s;
}

}  // namespace

Car::Car(b2World& world, double angle, double x, double y) : world_(world) {
  b2BodyDef hull_def;
  hull_def.type = b2_dynamicBody;
  hull_def.position.Set(static_cast<float>(x), static_cast<float>(y));
  hull_def.angle = static_cast<float>(angle);
  hull_ = world.CreateBody(&hull_def);
  for (const auto& points : kHullPolys) {
    const b2PolygonShape shape = polygon(points);
    b2FixtureDef fixture;  // pybox2d's defaults: friction 0.2, category 0x0001, mask 0xFFFF
    fixture.shape = &shape;
    fixture.density = 1.0f;
    hull_->CreateFixture(&fixture);
  }
  const b2PolygonShape wheel_shape = polygon(
      {{-kWheelW, +kWheelR}, {+kWheelW, +kWheelR}, {+kWheelW, -kWheelR}, {-kWheelW, -kWheelR}});
  for (size_t i = 0; i < wheels_.size(); ++i) {
    const auto [wx, wy] = kWheelPos[i];
    b2BodyDef def;
    def.type = b2_dynamicBody;
    // Gymnasium places the wheels at unrotated offsets; the joints pull them into place.
    def.position.Set(static_cast<float>(x + wx * kSize), static_cast<float>(y + wy * kSize));
    def.angle = static_cast<float>(angle);
    Wheel& w = wheels_[i];
    w.body = world.CreateBody(&def);
    b2FixtureDef fixture;
    fixture.shape = &wheel_shape;
    fixture.density = 0.1f;
    fixture.restitution = 0.0f;
    // Wheels touch the default category only (the road tiles; the hull is jointed to them).
    fixture.filter.categoryBits = 0x0020;
    fixture.filter.maskBits = 0x0001;
    w.body->CreateFixture(&fixture);

    b2RevoluteJointDef joint;
    joint.bodyA = hull_;
    joint.bodyB = w.body;
    joint.localAnchorA.Set(static_cast<float>(wx * kSize), static_cast<float>(wy * kSize));
    joint.localAnchorB.Set(0.0f, 0.0f);
    joint.referenceAngle = 0.0f;  // pybox2d: bodyB.angle - bodyA.angle, both `angle` here
    joint.enableMotor = true;
    joint.enableLimit = true;
    joint.maxMotorTorque = static_cast<float>(180 * 900 * kSize * kSize);
    joint.motorSpeed = 0.0f;
    joint.lowerAngle = -0.4f;
    joint.upperAngle = +0.4f;
    w.joint = static_cast<b2RevoluteJoint*>(world.CreateJoint(&joint));
  }
}

Car::~Car() {
  // Destroying a body destroys its joints too.
  world_.DestroyBody(hull_);
  for (Wheel& w : wheels_) world_.DestroyBody(w.body);
}

void Car::gas(double gas) {
  gas = std::clamp(gas, 0.0, 1.0);
  for (int i = 2; i < 4; ++i) {  // rear-wheel drive
    Wheel& w = wheels_[i];
    // "gradually increase, but stop immediately"
    w.gas += std::min(gas - w.gas, 0.1);
  }
}

void Car::brake(double brake) {
  for (Wheel& w : wheels_) w.brake = brake;
}

void Car::steer(double steer) {
  wheels_[0].steer = steer;
  wheels_[1].steer = steer;
}

void Car::remove_tile(int wheel, int tile) {
  std::vector<int>& tiles = wheels_[wheel].tiles;
  const auto it = std::find(tiles.begin(), tiles.end(), tile);
  if (it != tiles.end()) tiles.erase(it);
}

double Car::joint_angle(int wheel) const { return wheels_[wheel].joint->GetJointAngle(); }

void Car::steer_wheel(Wheel& w) {
  // The steering motor turns towards the target at up to 3 rad/s (50 per radian off).
  const double off = w.steer - w.joint->GetJointAngle();
  w.joint->SetMotorSpeed(static_cast<float>(sign(off) * std::min(50.0 * std::abs(off), 3.0)));
}

void Car::step(double dt) {
  for (Wheel& w : wheels_) {
    steer_wheel(w);
    // Grip: a road tile (road_friction 1) under the wheel, else grass at 60 %.
    const bool grass = w.tiles.empty();
    const double friction_limit = grass ? kFrictionLimit * 0.6 : kFrictionLimit;

    const b2Vec2 forw = w.body->GetWorldVector(b2Vec2(0.0f, 1.0f));
    const b2Vec2 side = w.body->GetWorldVector(b2Vec2(1.0f, 0.0f));
    const b2Vec2 v = w.body->GetLinearVelocity();
    const double vf = double{forw.x} * v.x + double{forw.y} * v.y;  // forward speed
    const double vs = double{side.x} * v.x + double{side.y} * v.y;  // side speed

    // The engine's power W = I omega domega/dt, so domega = dt W / I / omega; "+ 5" keeps
    // it finite at rest.
    w.omega += dt * kEnginePower * w.gas / kWheelMomentOfInertia / (std::abs(w.omega) + 5.0);
    if (w.brake >= 0.9) {
      w.omega = 0;
    } else if (w.brake > 0) {
      const double val = std::min(kBrakeForce * w.brake, std::abs(w.omega));  // low speed => 0
      w.omega += -sign(w.omega) * val;
    }
    w.phase += w.omega * dt;

    // The friction force drives the ground speed towards the wheel's rolling speed.
    double f_force = (-vf + w.omega * kWheelRad) * kForceCoefficient;
    double p_force = -vs * kForceCoefficient;
    const double force = std::sqrt(f_force * f_force + p_force * p_force);
    if (force > 2.0 * friction_limit)
      track_skid(w, grass);
    else
      end_skid(w);
    if (force > friction_limit) {
      f_force = f_force / force * friction_limit;
      p_force = p_force / force * friction_limit;
    }
    w.omega -= dt * f_force * kWheelRad / kWheelMomentOfInertia;
    w.body->ApplyForceToCenter(b2Vec2(static_cast<float>(p_force * side.x + f_force * forw.x),
                                      static_cast<float>(p_force * side.y + f_force * forw.y)),
                               true);
  }
}

// Skid marks: a skidding wheel extends its mark (same ground, under 30 points), or starts one
// from the position of the step before; at most 30 marks are kept.
void Car::track_skid(Wheel& w, bool grass) {
  const std::array<double, 2> here = {w.body->GetPosition().x, w.body->GetPosition().y};
  if (w.skid && w.skid->grass == grass && w.skid->points.size() < kMaxSkidPoints) {
    w.skid->points.push_back(here);
  } else if (!w.skid_start) {
    w.skid_start = here;
  } else {
    w.skid = std::make_shared<SkidMark>(SkidMark{{*w.skid_start, here}, grass});
    skid_marks_.push_back(w.skid);
    while (skid_marks_.size() > kMaxSkidMarks) skid_marks_.pop_front();
    w.skid_start.reset();
  }
}

void Car::end_skid(Wheel& w) {
  w.skid_start.reset();
  w.skid.reset();
}

CarState Car::state() const {
  CarState s;
  s.hull = body_state(hull_);
  for (size_t i = 0; i < wheels_.size(); ++i) {
    const Wheel& w = wheels_[i];
    WheelState& out = s.wheels[i];
    out.body = body_state(w.body);
    out.gas = w.gas;
    out.brake = w.brake;
    out.steer = w.steer;
    out.omega = w.omega;
    out.phase = w.phase;
    out.joint_angle = w.joint->GetJointAngle();
    out.tiles = static_cast<int>(w.tiles.size());
  }
  return s;
}

}  // namespace rlrun::car_racing
