// BipedalWalker-v3 (gymnasium/envs/box2d/bipedal_walker.py, Gymnasium 1.0): the world, the
// contact rules, the lidar, the observation and the reward. Every number comes from
// walker_constants.hpp, which cites Gymnasium's names.
#include "rlrun/envs/bipedal_walker/bipedal_walker.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <vector>

namespace rlrun {

using namespace walker;

// Gymnasium's ContactDetector: any contact of the hull ends the game (the hull collides with
// the ground only); the lower legs report whether they touch the ground.
class BipedalWalker::ContactDetector : public b2ContactListener {
 public:
  explicit ContactDetector(BipedalWalker& env) : env_(env) {}

  void BeginContact(b2Contact* contact) override {
    const b2Body* a = contact->GetFixtureA()->GetBody();
    const b2Body* b = contact->GetFixtureB()->GetBody();
    if (a == env_.hull_ || b == env_.hull_) env_.game_over_ = true;
    set_leg_contacts(a, b, true);
  }
  void EndContact(b2Contact* contact) override {
    set_leg_contacts(contact->GetFixtureA()->GetBody(), contact->GetFixtureB()->GetBody(), false);
  }

 private:
  void set_leg_contacts(const b2Body* a, const b2Body* b, bool touching) {
    for (const size_t leg : {size_t{1}, size_t{3}})  // self.env.legs[1], self.env.legs[3]
      if (env_.legs_[leg] == a || env_.legs_[leg] == b) env_.ground_contact_[leg] = touching;
  }
  BipedalWalker& env_;
};

// Gymnasium's LidarCallback: fixtures outside category 1 (the walker itself) are ignored
// (return -1); any other hit clips the ray (return fraction), so after World::RayCast the
// callback holds the closest ground hit, or fraction 1 when the ray hit nothing.
class BipedalWalker::LidarCallback : public b2RayCastCallback {
 public:
  float ReportFixture(b2Fixture* fixture, const b2Vec2& point, const b2Vec2& /*normal*/,
                      float fraction) override {
    if ((fixture->GetFilterData().categoryBits & kGroundCategory) == 0) return -1;
    end = point;
    this->fraction = fraction;
    return fraction;
  }
  b2Vec2 end{0, 0};
  float fraction = 1.0f;
};

namespace {

Space observation_box() {
  // BipedalWalker.__init__: joint speeds and velocities within 5 x their rated range ("due to
  // impulses from ground contact etc."), angles within pi, contacts in [0, 5], lidar [-1, 1].
  const float pi = static_cast<float>(M_PI);
  std::vector<float> high{pi, 5, 5, 5, pi, 5, pi, 5, 5, pi, 5, pi, 5, 5};
  std::vector<float> low{-pi, -5, -5, -5, -pi, -5, -pi, -5, -0.0f, -pi, -5, -pi, -5, -0.0f};
  high.insert(high.end(), kLidarRays, 1.0f);
  low.insert(low.end(), kLidarRays, -1.0f);
  return Space::box(std::move(low), std::move(high));
}

b2FixtureDef walker_fixture(const b2Shape& shape, double density) {
  b2FixtureDef fd;
  fd.shape = &shape;
  fd.density = static_cast<float>(density);
  fd.restitution = 0.0f;
  fd.filter.categoryBits = static_cast<uint16>(kWalkerCategory);
  fd.filter.maskBits = static_cast<uint16>(kGroundCategory);  // collide only with ground
  return fd;
}

b2Body* add_static_quad(b2World& world, const Quad& quad) {
  b2BodyDef def;  // CreateStaticBody(fixtures=self.fd_polygon)
  b2Body* body = world.CreateBody(&def);
  b2Vec2 corners[4];
  for (size_t k = 0; k < 4; ++k)
    corners[k].Set(static_cast<float>(quad[k].x), static_cast<float>(quad[k].y));
  b2PolygonShape shape;
  shape.Set(corners, 4);
  b2FixtureDef fd;  // fd_polygon: friction FRICTION, Box2D's default category 1
  fd.shape = &shape;
  fd.friction = static_cast<float>(kFriction);
  body->CreateFixture(&fd);
  return body;
}

}  // namespace

BipedalWalker::BipedalWalker(const Config& config)
    : config_(config),
      observation_space_(observation_box()),
      action_space_(Space::box(-1.0f, 1.0f, {kActSize})) {}

BipedalWalker::~BipedalWalker() {
  if (world_) world_->SetContactListener(nullptr);
}

std::string BipedalWalker::id() const {
  return config_.hardcore ? "BipedalWalkerHardcore-v3" : "BipedalWalker-v3";
}

void BipedalWalker::build_world() {
  if (world_) world_->SetContactListener(nullptr);
  world_ = std::make_unique<b2World>(b2Vec2(0.0f, -10.0f));  // pybox2d's b2World() gravity
  if (!contacts_) contacts_ = std::make_unique<ContactDetector>(*this);
  world_->SetContactListener(contacts_.get());

  for (const Obstacle& obstacle : terrain_.obstacles) add_static_quad(*world_, obstacle.corners);
  for (int i = 0; i + 1 < kTerrainLength; ++i) {  // the ground line: one edge per step
    b2BodyDef def;
    b2Body* body = world_->CreateBody(&def);
    b2EdgeShape edge;  // pybox2d 2.3's edges collide on both sides
    edge.SetTwoSided(
        b2Vec2(static_cast<float>(terrain_.x[i]), static_cast<float>(terrain_.y[i])),
        b2Vec2(static_cast<float>(terrain_.x[i + 1]), static_cast<float>(terrain_.y[i + 1])));
    b2FixtureDef fd;  // fd_edge
    fd.shape = &edge;
    fd.friction = static_cast<float>(kFriction);
    fd.filter.categoryBits = static_cast<uint16>(kGroundCategory);
    body->CreateFixture(&fd);
  }

  const double init_x = kTerrainStep * kTerrainStartpad / 2;
  const double init_y = kTerrainHeight + 2 * kLegH;
  b2BodyDef hull_def;
  hull_def.type = b2_dynamicBody;
  hull_def.position.Set(static_cast<float>(init_x), static_cast<float>(init_y));
  hull_ = world_->CreateBody(&hull_def);
  b2Vec2 hull_corners[5];
  for (size_t k = 0; k < 5; ++k)
    hull_corners[k].Set(static_cast<float>(kHullPoly[k][0] / kScale),
                        static_cast<float>(kHullPoly[k][1] / kScale));
  b2PolygonShape hull_shape;
  hull_shape.Set(hull_corners, 5);
  b2FixtureDef hull_fd = walker_fixture(hull_shape, kHullDensity);
  hull_fd.friction = static_cast<float>(kHullFriction);
  hull_->CreateFixture(&hull_fd);
  const double push = seeding_.rng().uniform(-kInitialRandom, kInitialRandom);
  hull_->ApplyForceToCenter(b2Vec2(static_cast<float>(push), 0.0f), true);

  b2PolygonShape leg_shape, lower_shape;
  leg_shape.SetAsBox(static_cast<float>(kLegW / 2), static_cast<float>(kLegH / 2));
  lower_shape.SetAsBox(static_cast<float>(0.8 * kLegW / 2), static_cast<float>(kLegH / 2));
  const b2FixtureDef leg_fd = walker_fixture(leg_shape, kLegDensity);
  const b2FixtureDef lower_fd = walker_fixture(lower_shape, kLegDensity);
  auto add_limb = [&](double y, double angle, const b2FixtureDef& fd) {
    b2BodyDef def;
    def.type = b2_dynamicBody;
    def.position.Set(static_cast<float>(init_x), static_cast<float>(y));
    def.angle = static_cast<float>(angle);
    b2Body* body = world_->CreateBody(&def);
    body->CreateFixture(&fd);
    return body;
  };
  // pybox2d's revoluteJointDef(bodyA=, bodyB=, ...) sets referenceAngle = bodyB.angle -
  // bodyA.angle (Box2D_joints.i), so each joint angle starts at 0.
  auto add_joint = [&](b2Body* a, b2Body* b, double anchor_a_y, double speed, double lower,
                       double upper) {
    b2RevoluteJointDef rjd;
    rjd.bodyA = a;
    rjd.bodyB = b;
    rjd.localAnchorA.Set(0.0f, static_cast<float>(anchor_a_y));
    rjd.localAnchorB.Set(0.0f, static_cast<float>(kLegH / 2));
    rjd.referenceAngle = b->GetAngle() - a->GetAngle();
    rjd.enableMotor = true;
    rjd.enableLimit = true;
    rjd.maxMotorTorque = static_cast<float>(kMotorsTorque);
    rjd.motorSpeed = static_cast<float>(speed);
    rjd.lowerAngle = static_cast<float>(lower);
    rjd.upperAngle = static_cast<float>(upper);
    return static_cast<b2RevoluteJoint*>(world_->CreateJoint(&rjd));
  };
  size_t k = 0;
  for (const int i : {-1, +1}) {
    const double angle = i * kLegStartAngle;
    b2Body* leg = add_limb(init_y - kLegH / 2 - kLegDown, angle, leg_fd);
    joints_[k] = add_joint(hull_, leg, kLegDown, i, kHipLower, kHipUpper);
    legs_[k++] = leg;
    b2Body* lower = add_limb(init_y - kLegH * 3 / 2 - kLegDown, angle, lower_fd);
    joints_[k] = add_joint(leg, lower, -kLegH / 2, 1, kKneeLower, kKneeUpper);
    legs_[k++] = lower;
  }
}

void BipedalWalker::reset(std::optional<uint64_t> seed, std::span<float> obs) {
  seeding_.on_reset(seed);  // gymnasium/core.py Env.reset (rlrun/env_seeding.hpp)
  terrain_ = generate_terrain(seeding_.rng(), config_.hardcore);
  game_over_ = false;
  has_prev_shaping_ = false;
  ground_contact_ = {};
  build_world();
  // Gymnasium's reset returns `self.step(np.array([0, 0, 0, 0]))[0]`: one simulated step with
  // the motors off, whose reward only sets prev_shaping.
  const float zero[kActSize] = {0, 0, 0, 0};
  step(zero, obs);
  episode_steps_ = 0;
  info_.clear();
}

StepResult BipedalWalker::step(std::span<const float> action, std::span<float> obs) {
  if (!hull_) throw std::logic_error(id() + ": call reset() before step()");
  if (action.size() != static_cast<size_t>(kActSize))
    throw std::invalid_argument(id() + ": an action has 4 values, got " +
                                std::to_string(action.size()));
  // Torque control (control_speed = False): full speed toward sign(a) with a torque budget
  // MOTORS_TORQUE * clip(|a|, 0, 1).
  constexpr double kSpeeds[kActSize] = {kSpeedHip, kSpeedKnee, kSpeedHip, kSpeedKnee};
  for (size_t j = 0; j < static_cast<size_t>(kActSize); ++j) {
    const float a = action[j];
    const double sign = a > 0 ? 1.0 : (a < 0 ? -1.0 : 0.0);  // np.sign
    joints_[j]->SetMotorSpeed(static_cast<float>(kSpeeds[j] * sign));
    joints_[j]->SetMaxMotorTorque(
        static_cast<float>(kMotorsTorque * std::clamp<double>(std::abs(a), 0.0, 1.0)));
  }
  return advance(action, obs);
}

StepResult BipedalWalker::advance(std::span<const float> action, std::span<float> obs) {
  world_->Step(static_cast<float>(1.0 / kFps), kVelocityIterations, kPositionIterations);
  ++episode_steps_;
  const b2Vec2 pos = hull_->GetPosition();
  const b2Vec2 vel = hull_->GetLinearVelocity();
  scan_lidar();

  const double angle = hull_->GetAngle();
  obs[0] = static_cast<float>(angle);
  obs[1] = static_cast<float>(2.0 * hull_->GetAngularVelocity() / kFps);
  obs[2] = static_cast<float>(0.3 * vel.x * (kViewportW / kScale) / kFps);
  obs[3] = static_cast<float>(0.3 * vel.y * (kViewportH / kScale) / kFps);
  for (size_t leg = 0; leg < 2; ++leg) {
    const b2RevoluteJoint* hip = joints_[2 * leg];
    const b2RevoluteJoint* knee = joints_[2 * leg + 1];
    float* o = obs.data() + 4 + 5 * leg;
    o[0] = hip->GetJointAngle();
    o[1] = static_cast<float>(hip->GetJointSpeed() / kSpeedHip);
    o[2] = static_cast<float>(knee->GetJointAngle() + 1.0);
    o[3] = static_cast<float>(knee->GetJointSpeed() / kSpeedKnee);
    o[4] = ground_contact_[2 * leg + 1] ? 1.0f : 0.0f;
  }
  for (size_t i = 0; i < static_cast<size_t>(kLidarRays); ++i) obs[14 + i] = lidar_fraction_[i];

  // Moving forward is rewarded (about 300 on reaching the end); keeping the head straight is
  // the only other shaping. The first step after a reset only records the shaping.
  const double shaping = 130 * pos.x / kScale - 5.0 * std::abs(static_cast<double>(obs[0]));
  StepResult result;
  if (has_prev_shaping_) result.reward = shaping - prev_shaping_;
  prev_shaping_ = shaping;
  has_prev_shaping_ = true;
  for (const float a : action)  // "normalized to about -50.0 using heuristic"
    result.reward -= 0.00035 * kMotorsTorque * std::clamp<double>(std::abs(a), 0.0, 1.0);

  if (game_over_ || pos.x < 0) {
    result.reward = -100;
    result.terminated = true;
  }
  if (pos.x > (kTerrainLength - kTerrainGrass) * kTerrainStep) result.terminated = true;
  info_.clear();
  return result;
}

void BipedalWalker::scan_lidar() {
  // Ray i leaves the hull's origin at 1.5 * i / 10 rad from straight down, forward.
  const b2Vec2 p1 = hull_->GetPosition();
  lidar_start_ = p1;
  for (size_t i = 0; i < static_cast<size_t>(kLidarRays); ++i) {
    LidarCallback ray;
    const double theta = 1.5 * static_cast<double>(i) / 10.0;
    const b2Vec2 p2(static_cast<float>(p1.x + std::sin(theta) * kLidarRange),
                    static_cast<float>(p1.y - std::cos(theta) * kLidarRange));
    ray.end = p2;
    world_->RayCast(&ray, p1, p2);
    lidar_fraction_[i] = ray.fraction;
    lidar_end_[i] = ray.end;
  }
}

std::array<b2Vec2, 2> BipedalWalker::lidar_ray(int i) const {
  return {lidar_start_, lidar_end_[static_cast<size_t>(i)]};
}

}  // namespace rlrun
