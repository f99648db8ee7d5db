#include "rlrun/envs/car_racing/car_racing.hpp"

#include <box2d/box2d.h>

#include <cmath>
#include <stdexcept>

#include "rlrun/env/discrete_action.hpp"
#include "rlrun/envs/car_racing/car_dynamics.hpp"
#include "rlrun/render/polygon_canvas.hpp"

namespace rlrun {

namespace {

using car_racing::Car;
// world.Step(1.0 / FPS, 6 * 30, 2 * 30): velocity and position iterations.
constexpr int kVelocityIterations = 6 * 30, kPositionIterations = 2 * 30;
// Samples per observation pixel and axis: Gymnasium shrinks a 1000x800 window to 96x96, about
// 10x8 window pixels per observation pixel; 4x4 samples give the same smooth edges.
constexpr int kStateSupersample = 4;

// What a Box2D body is, in its user data: a road tile or a wheel (the hull has none).
enum class BodyKind : uintptr_t { kNone = 0, kTile = 1, kWheel = 2 };
uintptr_t tag(BodyKind kind, int index) {
  return (static_cast<uintptr_t>(index) << 2) | static_cast<uintptr_t>(kind);
}
BodyKind kind_of(b2Body* body) { return static_cast<BodyKind>(body->GetUserData().pointer & 3); }
int index_of(b2Body* body) { return static_cast<int>(body->GetUserData().pointer >> 2); }

Space make_action_space(bool continuous) {
  if (!continuous) return Space::discrete(5);                  // nothing, left, right, gas, brake
  return Space::box({-1.0f, 0.0f, 0.0f}, {1.0f, 1.0f, 1.0f});  // steer, gas, brake
}

}  // namespace

// One episode's world: the road tiles (static sensors) and the car, and Gymnasium's
// FrictionDetector, which tells the env when a wheel starts or stops touching a tile.
struct CarRacing::Physics : public b2ContactListener {
  explicit Physics(CarRacing& env) : world(b2Vec2(0.0f, 0.0f)), env(env) {
    world.SetContactListener(this);
  }
  ~Physics() override {
    world.SetContactListener(nullptr);
    car.reset();  // before the world that owns its bodies
  }
  void BeginContact(b2Contact* contact) override { on_contact(contact, true); }
  void EndContact(b2Contact* contact) override { on_contact(contact, false); }

  void on_contact(b2Contact* contact, bool begin) {
    b2Body* a = contact->GetFixtureA()->GetBody();
    b2Body* b = contact->GetFixtureB()->GetBody();
    if (kind_of(b) == BodyKind::kTile) std::swap(a, b);
    if (kind_of(a) != BodyKind::kTile) return;
    env.on_tile_contact(index_of(a), kind_of(b) == BodyKind::kWheel ? index_of(b) : -1, begin);
  }

  b2World world;
  CarRacing& env;
  std::vector<b2Body*> tiles;
  std::unique_ptr<Car> car;
};

CarRacing::CarRacing(const Config& config)
    : config_(config),
      observation_space_(Space::image({kStateSize, kStateSize, 3})),
      action_space_(make_action_space(config.continuous)),
      lap_finished_key_(info_.add_key("lap_finished")) {
  if (!(config.lap_complete_percent >= 0.0 && config.lap_complete_percent <= 1.0))
    throw std::invalid_argument("lap_complete_percent must lie in [0, 1], got " +
                                std::to_string(config.lap_complete_percent));
}

CarRacing::~CarRacing() = default;

void CarRacing::set_next_track(std::vector<TrackPoint> track) {
  car_racing::check_track(track);
  next_track_ = std::move(track);
}

const car_racing::Car& CarRacing::car_model() const { return *physics_->car; }

CarState CarRacing::car() const {
  if (!physics_) throw std::logic_error(id() + ": no car before reset()");
  return physics_->car->state();
}

// CarRacing._reinit_colors: road and background uniform in [0, 210) per channel, the grass
// the background's colour with 20 more in one random channel.
void CarRacing::draw_colors() {
  Rng& rng = seeding_.rng();
  for (double& c : colors_.road) c = rng.uniform(0.0, 210.0);
  for (double& c : colors_.bg) c = rng.uniform(0.0, 210.0);
  colors_.grass = colors_.bg;
  colors_.grass[rng.below(3)] += 20;
}

void CarRacing::reset(std::optional<uint64_t> seed, std::span<float> obs) {
  seeding_.on_reset(seed);
  info_.clear();
  // Gymnasium also draws colours in __init__, from an unseeded generator; rlrun draws its
  // first ones at the first reset, from the seeded one, so every episode is reproducible.
  if (config_.domain_randomize && (next_randomize_ || !colors_drawn_)) {
    draw_colors();
    colors_drawn_ = true;
  }
  next_randomize_ = true;
  physics_.reset();  // the old world goes before the counters its listener updates
  reward_ = prev_reward_ = t_ = 0;
  tile_visited_count_ = 0;
  new_lap_ = false;

  if (next_track_) {
    track_ = std::move(*next_track_);
    next_track_.reset();
  } else {
    while (true) {  // "retry to generate track (normal if there are not many...)"
      if (auto track = car_racing::generate_track(seeding_.rng())) {
        track_ = std::move(*track);
        break;
      }
    }
  }
  road_ = car_racing::build_road(track_);
  tile_touched_.assign(road_.tiles.size(), false);
  tile_visited_.assign(road_.tiles.size(), false);

  physics_ = std::make_unique<Physics>(*this);
  for (size_t i = 0; i < road_.tiles.size(); ++i) {
    b2BodyDef def;  // static
    def.userData.pointer = tag(BodyKind::kTile, static_cast<int>(i));
    b2Body* tile = physics_->world.CreateBody(&def);
    b2Vec2 vertices[4];
    for (int k = 0; k < 4; ++k)
      vertices[k].Set(static_cast<float>(road_.tiles[i][k][0]),
                      static_cast<float>(road_.tiles[i][k][1]));
    b2PolygonShape shape;
    shape.Set(vertices, 4);
    b2FixtureDef fixture;
    fixture.shape = &shape;
    fixture.isSensor = true;  // the car drives over tiles; contacts only report them
    tile->CreateFixture(&fixture);
    physics_->tiles.push_back(tile);
  }
  const TrackPoint& start = track_.front();
  physics_->car = std::make_unique<Car>(physics_->world, start.beta, start.x, start.y);
  for (int w = 0; w < 4; ++w)
    physics_->car->wheel_body(w)->GetUserData().pointer = tag(BodyKind::kWheel, w);

  advance(std::nullopt, obs);  // Gymnasium: return self.step(None)[0], {}
  info_.clear();
}

// FrictionDetector._contact: anything touching a tile recolours it plain road; a wheel's
// first touch of an unvisited tile pays 1000/N, and reaching tile 0 again with more than
// lap_complete_percent of the tiles visited finishes the lap.
void CarRacing::on_tile_contact(int tile, int wheel, bool begin) {
  tile_touched_[tile] = true;
  if (wheel < 0) return;
  Car& car = *physics_->car;
  if (!begin) {
    car.remove_tile(wheel, tile);
    return;
  }
  car.add_tile(wheel, tile);
  if (tile_visited_[tile]) return;
  tile_visited_[tile] = true;
  const double n = static_cast<double>(track_.size());
  reward_ += 1000.0 / n;
  ++tile_visited_count_;
  if (tile == 0 && tile_visited_count_ / n > config_.lap_complete_percent) new_lap_ = true;
}

void CarRacing::apply_action(std::span<const float> action) {
  Car& car = *physics_->car;
  if (config_.continuous) {
    if (action.size() != 3) throw std::invalid_argument(id() + ": an action has 3 values");
    for (const float a : action)
      if (!std::isfinite(a)) throw std::invalid_argument(id() + ": the action is not finite");
    // Gymnasium: steer(-action[0]) (the joint's positive angle turns left), gas clipped to
    // [0, 1] by the car, brake as given.
    car.steer(-static_cast<double>(action[0]));
    car.gas(action[1]);
    car.brake(action[2]);
    return;
  }
  const int a = checked_discrete_action(action_space_, action, id());
  car.steer(-0.6 * (a == 1) + 0.6 * (a == 2));
  car.gas(0.2 * (a == 3));
  car.brake(0.8 * (a == 4));
}

StepResult CarRacing::step(std::span<const float> action, std::span<float> obs) {
  if (!physics_) throw std::logic_error(id() + ": step() before reset()");
  return advance(action, obs);
}

// Gymnasium's step(action), where reset() passes None: no controls, no reward, no end.
StepResult CarRacing::advance(std::optional<std::span<const float>> action, std::span<float> obs) {
  info_.clear();
  if (action) apply_action(*action);
  physics_->car->step(1.0 / kFps);
  physics_->world.Step(static_cast<float>(1.0 / kFps), kVelocityIterations, kPositionIterations);
  t_ += 1.0 / kFps;

  if (!state_canvas_)
    state_canvas_ = std::make_unique<PolygonCanvas>(kStateSize, kStateSize, kStateSupersample);
  draw_scene(*state_canvas_, false);
  state_pixels_.resize(static_cast<size_t>(kStateSize) * kStateSize * 3);
  state_canvas_->resolve(state_pixels_);
  for (size_t i = 0; i < state_pixels_.size(); ++i) obs[i] = state_pixels_[i];

  StepResult result;
  if (!action) return result;
  reward_ -= 0.1;
  result.reward = reward_ - prev_reward_;
  prev_reward_ = reward_;
  if (tile_visited_count_ == static_cast<int>(track_.size()) || new_lap_) {
    result.terminated = true;
    info_.set(lap_finished_key_, 1.0);
  }
  const b2Vec2 position = physics_->car->hull()->GetPosition();
  if (std::abs(position.x) > car_racing::kPlayfield ||
      std::abs(position.y) > car_racing::kPlayfield) {
    result.terminated = true;
    info_.set(lap_finished_key_, 0.0);
    result.reward = -100;
  }
  return result;
}

}  // namespace rlrun
