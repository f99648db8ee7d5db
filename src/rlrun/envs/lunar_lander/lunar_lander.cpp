#include "rlrun/envs/lunar_lander/lunar_lander.hpp"

#include <box2d/box2d.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include "rlrun/env/discrete_action.hpp"

namespace rlrun {

namespace {

// Module constants of gymnasium/envs/box2d/lunar_lander.py (Gymnasium 1.0.0),
// same names.
constexpr double kFps = 50;                // FPS: world steps per second, render_fps
constexpr double kScale = 30.0;            // SCALE: pixels per world unit
constexpr double kMainEnginePower = 13.0;  // MAIN_ENGINE_POWER
constexpr double kSideEnginePower = 0.6;   // SIDE_ENGINE_POWER
constexpr double kInitialRandom = 1000.0;  // INITIAL_RANDOM: max initial force per axis
// LANDER_POLY, pixels: the hull's six corners.
constexpr double kLanderPoly[6][2] = {{-14, +17}, {-17, 0}, {-17, -10},
                                      {+17, -10}, {+17, 0}, {+14, +17}};
constexpr double kLegAway = 20;  // LEG_AWAY: leg anchor's side offset, pixels
constexpr double kLegDown = 18;  // LEG_DOWN: leg anchor's drop, pixels
constexpr double kLegW = 2,
                 kLegH = 8;                 // LEG_W, LEG_H: leg box half-extents, pixels
constexpr double kLegSpringTorque = 40;     // LEG_SPRING_TORQUE: leg joint motor torque
constexpr double kSideEngineHeight = 14;    // SIDE_ENGINE_HEIGHT, pixels
constexpr double kSideEngineAway = 12;      // SIDE_ENGINE_AWAY, pixels
constexpr double kMainEngineYLocation = 4;  // MAIN_ENGINE_Y_LOCATION, pixels
constexpr double kViewportW = 600;          // VIEWPORT_W
constexpr double kViewportH = 400;          // VIEWPORT_H
constexpr double kW = kViewportW / kScale;  // W in reset(): world width, 20
constexpr double kH = kViewportH / kScale;  // H in reset(): world height, 13.33
// Collision filtering of reset(): the moon keeps Box2D's default category
// 0x0001; the hull (0x0010) and legs (0x0020) collide with the ground only,
// never with each other.
constexpr uint16 kHullCategory = 0x0010, kLegCategory = 0x0020, kGroundMask = 0x0001;
// world.Step(1.0 / FPS, 6 * 30, 2 * 30): velocity and position iterations.
constexpr int kVelocityIterations = 6 * 30, kPositionIterations = 2 * 30;

Space make_observation_space() {
  // v3 bounds (Gymnasium 1.0 widened v2's +-1.5, +-5, +-pi, issue #752);
  // float32.
  constexpr float kTwoPi = static_cast<float>(2 * std::numbers::pi);
  return Space::box({-2.5f, -2.5f, -10.0f, -10.0f, -kTwoPi, -10.0f, -0.0f, -0.0f},
                    {2.5f, 2.5f, 10.0f, 10.0f, kTwoPi, 10.0f, 1.0f, 1.0f});
}

// Gymnasium's wind and turbulence profile: tanh(sin(2 k t) + sin(pi k t)), k =
// 0.01, never periodic; t is an integer index that advances once per windy
// step.
double wind_profile(int index) {
  return std::tanh(std::sin(0.02 * index) + std::sin(std::numbers::pi * 0.01 * index));
}

}  // namespace

// The Box2D world of one episode and Gymnasium's ContactDetector: a contact
// involving the hull ends the game, a leg's contacts set and clear its
// ground_contact flag.
struct LunarLander::Physics : public b2ContactListener {
  explicit Physics(LunarLander& env)
      : world(b2Vec2(0.0f, static_cast<float>(env.config_.gravity))), env(env) {
    world.SetContactListener(this);
  }
  // No callbacks into a half-destroyed listener while the world tears down.
  ~Physics() override { world.SetContactListener(nullptr); }
  void BeginContact(b2Contact* contact) override {
    const b2Body* a = contact->GetFixtureA()->GetBody();
    const b2Body* b = contact->GetFixtureB()->GetBody();
    if (a == lander || b == lander) env.game_over_ = true;
    for (int i = 0; i < 2; ++i)
      if (a == legs[i] || b == legs[i]) env.ground_contact_[i] = true;
  }
  void EndContact(b2Contact* contact) override {
    const b2Body* a = contact->GetFixtureA()->GetBody();
    const b2Body* b = contact->GetFixtureB()->GetBody();
    for (int i = 0; i < 2; ++i)
      if (a == legs[i] || b == legs[i]) env.ground_contact_[i] = false;
  }

  b2World world;
  LunarLander& env;
  b2Body* moon = nullptr;
  b2Body* lander = nullptr;
  b2Body* legs[2] = {nullptr, nullptr};
};

LunarLander::LunarLander(const Config& config)
    : config_(config),
      observation_space_(make_observation_space()),
      action_space_(config.continuous ? Space::box(-1.0f, 1.0f, {2}) : Space::discrete(4)) {
  // assert -12.0 < gravity and gravity < 0.0 (LunarLander.__init__).
  if (!(-12.0 < config.gravity && config.gravity < 0.0))
    throw std::invalid_argument("gravity (current value: " + std::to_string(config.gravity) +
                                ") must be between -12 and 0");
}

LunarLander::~LunarLander() = default;

bool LunarLander::lander_awake() const { return physics_ && physics_->lander->IsAwake(); }

void LunarLander::reset(std::optional<uint64_t> seed, std::span<float> obs) {
  seeding_.on_reset(seed);
  Rng& rng = seeding_.rng();
  info_.clear();
  physics_.reset();  // destroy the old world before its listener's flags are cleared
  game_over_ = false;
  ground_contact_ = {false, false};
  prev_shaping_.reset();
  physics_ = std::make_unique<Physics>(*this);
  b2World& world = physics_->world;

  // Terrain: CHUNKS + 1 random heights in [0, H/2), the five around the middle
  // flattened to the helipad's height H/4, then each chunk's height smoothed
  // over its neighbours (the factor is 0.33, not 1/3, in Gymnasium; height[-1]
  // wraps around as in Python).
  std::array<double, kChunks + 1> height{};
  for (double& h : height) h = rng.uniform(0.0, kH / 2);
  for (int i = 0; i < kChunks; ++i) chunk_x_[i] = kW / (kChunks - 1) * i;
  helipad_x1_ = chunk_x_[kChunks / 2 - 1];
  helipad_x2_ = chunk_x_[kChunks / 2 + 1];
  helipad_y_ = kH / 4;
  for (int i = kChunks / 2 - 2; i <= kChunks / 2 + 2; ++i) height[i] = helipad_y_;
  for (int i = 0; i < kChunks; ++i) {
    const double before = height[i == 0 ? kChunks : i - 1];
    smooth_y_[i] = 0.33 * (before + height[i] + height[i + 1]);
  }

  // The moon: a static body with a floor edge along y = 0 (fixture defaults:
  // friction 0.2) and one edge per chunk (friction 0.1).
  b2BodyDef moon_def;
  physics_->moon = world.CreateBody(&moon_def);
  b2EdgeShape edge;
  edge.SetTwoSided(b2Vec2(0.0f, 0.0f), b2Vec2(static_cast<float>(kW), 0.0f));
  b2FixtureDef floor;
  floor.shape = &edge;
  physics_->moon->CreateFixture(&floor);
  for (int i = 0; i + 1 < kChunks; ++i) {
    edge.SetTwoSided(
        b2Vec2(static_cast<float>(chunk_x_[i]), static_cast<float>(smooth_y_[i])),
        b2Vec2(static_cast<float>(chunk_x_[i + 1]), static_cast<float>(smooth_y_[i + 1])));
    b2FixtureDef chunk;
    chunk.shape = &edge;
    chunk.density = 0.0f;
    chunk.friction = 0.1f;
    physics_->moon->CreateFixture(&chunk);
  }

  // The lander's hull at the top centre, density 5, friction 0.1, no bounce.
  const double initial_x = kViewportW / kScale / 2, initial_y = kViewportH / kScale;
  b2BodyDef hull_def;
  hull_def.type = b2_dynamicBody;
  hull_def.position.Set(static_cast<float>(initial_x), static_cast<float>(initial_y));
  hull_def.angle = 0.0f;
  b2Body* lander = world.CreateBody(&hull_def);
  physics_->lander = lander;
  b2Vec2 corners[6];
  for (int i = 0; i < 6; ++i)
    corners[i].Set(static_cast<float>(kLanderPoly[i][0] / kScale),
                   static_cast<float>(kLanderPoly[i][1] / kScale));
  b2PolygonShape hull;
  hull.Set(corners, 6);
  b2FixtureDef hull_fixture;
  hull_fixture.shape = &hull;
  hull_fixture.density = 5.0f;
  hull_fixture.friction = 0.1f;
  hull_fixture.restitution = 0.0f;
  hull_fixture.filter.categoryBits = kHullCategory;
  hull_fixture.filter.maskBits = kGroundMask;
  lander->CreateFixture(&hull_fixture);

  // The initial random push, applied during the first step (the reset's no-op
  // step).
  const double fx = rng.uniform(-kInitialRandom, kInitialRandom);
  const double fy = rng.uniform(-kInitialRandom, kInitialRandom);
  lander->ApplyForceToCenter(b2Vec2(static_cast<float>(fx), static_cast<float>(fy)), true);

  // v3: the wind and turbulence offsets C are drawn at every reset, from the
  // env's RNG and only with wind on (np_random.integers(-9999, 9999): -9999 ..
  // 9998).
  if (config_.enable_wind) {
    wind_idx_ = -9999 + static_cast<int>(rng.below(19998));
    torque_idx_ = -9999 + static_cast<int>(rng.below(19998));
  }

  // Legs (i = -1 left, +1 right): boxes hinged below the hull by a motorised
  // revolute joint with Gymnasium's "esoteric" limits; the motor works as a
  // spring pushing the legs apart.
  for (int k = 0; k < 2; ++k) {
    const int i = k == 0 ? -1 : +1;
    b2BodyDef leg_def;
    leg_def.type = b2_dynamicBody;
    leg_def.position.Set(static_cast<float>(initial_x - i * kLegAway / kScale),
                         static_cast<float>(initial_y));
    leg_def.angle = static_cast<float>(i * 0.05);
    b2Body* leg = world.CreateBody(&leg_def);
    b2PolygonShape box;
    box.SetAsBox(static_cast<float>(kLegW / kScale), static_cast<float>(kLegH / kScale));
    b2FixtureDef leg_fixture;
    leg_fixture.shape = &box;
    leg_fixture.density = 1.0f;
    leg_fixture.restitution = 0.0f;
    leg_fixture.filter.categoryBits = kLegCategory;
    leg_fixture.filter.maskBits = kGroundMask;
    leg->CreateFixture(&leg_fixture);

    b2RevoluteJointDef joint;
    joint.bodyA = lander;
    joint.bodyB = leg;
    joint.localAnchorA.Set(0.0f, 0.0f);
    joint.localAnchorB.Set(static_cast<float>(i * kLegAway / kScale),
                           static_cast<float>(kLegDown / kScale));
    joint.enableMotor = true;
    joint.enableLimit = true;
    joint.maxMotorTorque = static_cast<float>(kLegSpringTorque);
    joint.motorSpeed = static_cast<float>(+0.3 * i);  // "low enough not to jump back into the sky"
    joint.lowerAngle = static_cast<float>(i == -1 ? +0.9 - 0.5 : -0.9);
    joint.upperAngle = static_cast<float>(i == -1 ? +0.9 : -0.9 + 0.5);
    world.CreateJoint(&joint);
    physics_->legs[k] = leg;
  }

  // return self.step(np.array([0, 0]) if self.continuous else 0)[0], {}
  const float noop[2] = {0.0f, 0.0f};
  step(std::span<const float>(noop, config_.continuous ? 2 : 1), obs);
  info_.clear();
}

void LunarLander::apply_wind() {
  // Only while neither leg touches the ground (step(): "Update wind and apply
  // to the lander").
  if (!config_.enable_wind || ground_contact_[0] || ground_contact_[1]) return;
  b2Body* lander = physics_->lander;
  const double wind_mag = wind_profile(wind_idx_) * config_.wind_power;
  ++wind_idx_;
  lander->ApplyForceToCenter(b2Vec2(static_cast<float>(wind_mag), 0.0f), true);
  const double torque_mag = wind_profile(torque_idx_) * config_.turbulence_power;
  ++torque_idx_;
  lander->ApplyTorque(static_cast<float>(torque_mag), true);
}

void LunarLander::fire_engines(std::span<const float> action) {
  // Throttles: discrete actions fire at full power; continuous ones are clipped
  // to [-1, 1], the main engine fires for main > 0 at 50..100 % ((clip(main, 0,
  // 1) + 1) / 2), the side engines for |lateral| > 0.5 at clip(|lateral|, 0.5,
  // 1), left below -0.5, right above.
  double main = 0.0, lateral = 0.0;
  int discrete = kNoop;
  if (config_.continuous) {
    main = std::clamp(static_cast<double>(action[0]), -1.0, 1.0);
    lateral = std::clamp(static_cast<double>(action[1]), -1.0, 1.0);
  } else {
    discrete = checked_discrete_action(action_space_, action, id());
  }
  b2Body* lander = physics_->lander;
  const double angle = lander->GetAngle();
  const double tip[2] = {std::sin(angle), std::cos(angle)};  // the hull's up axis
  const double side[2] = {-tip[1], tip[0]};
  // Two draws every step, fired or not, as in Gymnasium: dispersion in [-1, 1)
  // / SCALE.
  Rng& rng = seeding_.rng();
  const double d0 = rng.uniform(-1.0, 1.0) / kScale;
  const double dispersion[2] = {d0, rng.uniform(-1.0, 1.0) / kScale};
  const b2Vec2 position = lander->GetPosition();

  m_power_ = 0.0;
  if ((config_.continuous && main > 0.0) || (!config_.continuous && discrete == kMainEngine)) {
    m_power_ = config_.continuous ? (std::clamp(main, 0.0, 1.0) + 1.0) * 0.5 : 1.0;
    // "4 is move a bit downwards, +-2 for randomness": the impulse acts below
    // the centre.
    const double ox =
        tip[0] * (kMainEngineYLocation / kScale + 2 * dispersion[0]) + side[0] * dispersion[1];
    const double oy =
        -tip[1] * (kMainEngineYLocation / kScale + 2 * dispersion[0]) - side[1] * dispersion[1];
    const b2Vec2 at(static_cast<float>(position.x + ox), static_cast<float>(position.y + oy));
    lander->ApplyLinearImpulse(b2Vec2(static_cast<float>(-ox * kMainEnginePower * m_power_),
                                      static_cast<float>(-oy * kMainEnginePower * m_power_)),
                               at, true);
  }

  s_power_ = 0.0;
  if ((config_.continuous && std::abs(lateral) > 0.5) ||
      (!config_.continuous && (discrete == kLeftEngine || discrete == kRightEngine))) {
    double direction;
    if (config_.continuous) {
      direction = lateral > 0 ? 1.0 : -1.0;  // np.sign; |lateral| > 0.5 here
      s_power_ = std::clamp(std::abs(lateral), 0.5, 1.0);
    } else {
      direction = discrete - 2;  // 1 (left) -> -1, 3 (right) -> +1
      s_power_ = 1.0;
    }
    const double ox = tip[0] * dispersion[0] +
                      side[0] * (3 * dispersion[1] + direction * kSideEngineAway / kScale);
    const double oy = -tip[1] * dispersion[0] -
                      side[1] * (3 * dispersion[1] + direction * kSideEngineAway / kScale);
    // Gymnasium writes 17 here, not SIDE_ENGINE_HEIGHT (14): the thrust point
    // moves with the hull's orientation, an orientation-dependent torque its
    // docs list as a known quirk.
    const b2Vec2 at(static_cast<float>(position.x + ox - tip[0] * 17 / kScale),
                    static_cast<float>(position.y + oy + tip[1] * kSideEngineHeight / kScale));
    lander->ApplyLinearImpulse(b2Vec2(static_cast<float>(-ox * kSideEnginePower * s_power_),
                                      static_cast<float>(-oy * kSideEnginePower * s_power_)),
                               at, true);
  }
}

StepResult LunarLander::step(std::span<const float> action, std::span<float> obs) {
  if (!physics_) throw std::logic_error(id() + ": step() before reset()");
  info_.clear();
  apply_wind();
  fire_engines(action);
  physics_->world.Step(static_cast<float>(1.0 / kFps), kVelocityIterations, kPositionIterations);

  const std::array<double, kObsSize> s = state();
  for (int i = 0; i < kObsSize; ++i) obs[i] = static_cast<float>(s[i]);
  // "ten points for legs contact, the idea is if you lose contact again after
  // landing, you get negative reward": the reward is the change of this
  // potential.
  const double shaping = -100 * std::sqrt(s[0] * s[0] + s[1] * s[1]) -
                         100 * std::sqrt(s[2] * s[2] + s[3] * s[3]) - 100 * std::abs(s[4]) +
                         10 * s[6] + 10 * s[7];
  double reward = prev_shaping_ ? shaping - *prev_shaping_ : 0.0;
  prev_shaping_ = shaping;
  reward -= m_power_ * 0.30;  // "less fuel spent is better, about -30 for heuristic landing"
  reward -= s_power_ * 0.03;

  bool terminated = false;
  if (game_over_ || std::abs(s[0]) >= 1.0) {
    terminated = true;
    reward = -100;
  }
  if (!physics_->lander->IsAwake()) {  // came to rest: Box2D put the lander's
                                       // island to sleep
    terminated = true;
    reward = +100;
  }
  return {reward, terminated, false};
}

std::array<double, LunarLander::kObsSize> LunarLander::state() const {
  const b2Body* lander = physics_->lander;
  const b2Vec2 pos = lander->GetPosition();
  const b2Vec2 vel = lander->GetLinearVelocity();
  // Positions relative to the pad (x to its centre, y to the height of the
  // legs' anchors on the pad) in half-viewports, velocities in half-viewports
  // per frame; the angular velocity is in 20 / FPS = 0.4 rad/s units
  // (Gymnasium's notes list these units).
  return {(pos.x - kViewportW / kScale / 2) / (kViewportW / kScale / 2),
          (pos.y - (helipad_y_ + kLegDown / kScale)) / (kViewportH / kScale / 2),
          vel.x * (kViewportW / kScale / 2) / kFps,
          vel.y * (kViewportH / kScale / 2) / kFps,
          lander->GetAngle(),
          20.0 * lander->GetAngularVelocity() / kFps,
          ground_contact_[0] ? 1.0 : 0.0,
          ground_contact_[1] ? 1.0 : 0.0};
}

std::array<std::array<double, 2>, 6> LunarLander::hull_outline() const {
  std::array<std::array<double, 2>, 6> out{};
  if (!physics_) return out;
  const b2Transform& t = physics_->lander->GetTransform();
  const auto* shape =
      static_cast<const b2PolygonShape*>(physics_->lander->GetFixtureList()->GetShape());
  for (int i = 0; i < 6 && i < shape->m_count; ++i) {
    const b2Vec2 p = b2Mul(t, shape->m_vertices[i]);
    out[i] = {p.x, p.y};
  }
  return out;
}

std::array<std::array<double, 2>, 4> LunarLander::leg_outline(int leg) const {
  std::array<std::array<double, 2>, 4> out{};
  if (!physics_) return out;
  const b2Body* body = physics_->legs[leg];
  const b2Transform& t = body->GetTransform();
  const auto* shape = static_cast<const b2PolygonShape*>(body->GetFixtureList()->GetShape());
  for (int i = 0; i < 4; ++i) {
    const b2Vec2 p = b2Mul(t, shape->m_vertices[i]);
    out[i] = {p.x, p.y};
  }
  return out;
}

}  // namespace rlrun
