// CarRacing-v3's rules (gymnasium/envs/box2d/car_racing.py and car_dynamics.py, Gymnasium
// 1.0.0) on Box2D 2.4: spaces and registration, the track generator's geometry, the road and
// kerbs, the car's drive, brakes and steering (car_dynamics.py's equations checked against the
// state they act on), grip on road and grass, the tile reward and lap end, leaving the
// playfield, a track set from outside, domain randomisation, the picture, the env checker and
// the CLI. No pybox2d exists here, so no Gymnasium trajectory is compared (docs/car_racing.md).
#include <catch2/catch.hpp>
#include <chrono>
#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "rlrun/env/env_checker.hpp"
#include "rlrun/envs/car_racing/car_dynamics.hpp"
#include "rlrun/envs/car_racing/car_racing.hpp"
#include "rlrun/envs/car_racing/line_follower.hpp"
#include "rlrun/envs/car_racing/race_track.hpp"
#include "rlrun/frame.hpp"
#include "rlrun/runtime/components/builtins.hpp"
#include "rlrun/wrappers/time_limit.hpp"
#include "runtime/cli_runner.hpp"
#include "runtime/video_probe.hpp"

using namespace rlrun;
using namespace rlrun::car_racing;
using namespace rlrun::testing;

namespace {

using Vec = std::vector<float>;
constexpr size_t kObsSize = 96 * 96 * 3;

StepResult drive(CarRacing& env, float steer, float gas, float brake, Vec& obs) {
  const float a[3] = {steer, gas, brake};
  return env.step({a, 3}, obs);
}

std::array<uint8_t, 3> pixel(const Vec& obs, int x, int y) {
  const size_t i = (static_cast<size_t>(y) * 96 + x) * 3;
  return {static_cast<uint8_t>(obs[i]), static_cast<uint8_t>(obs[i + 1]),
          static_cast<uint8_t>(obs[i + 2])};
}

double speed(const CarState& car) {
  return std::hypot(car.hull.linear_velocity[0], car.hull.linear_velocity[1]);
}

// A straight track along +y from (x0, y0) (beta 0: the car faces +y), `n` points apart by
// TRACK_DETAIL_STEP. Its last point sits one step behind the first, so tile 0 lies under the
// car's rear wheels as on a closed track (tile n - 1 then spans the whole straight).
std::vector<TrackPoint> straight_track(double x0, double y0, int n) {
  std::vector<TrackPoint> track;
  for (int i = 0; i + 1 < n; ++i) track.push_back({0, 0, x0, y0 + i * kTrackDetailStep});
  track.push_back({0, 0, x0, y0 - kTrackDetailStep});
  return track;
}

}  // namespace

TEST_CASE("car racing: spaces, registration and kwargs", "[car_racing]") {
  CarRacing env;
  CHECK(env.id() == "CarRacing-v3");
  CHECK(env.observation_space().describe() == "Box(0, 255, (96, 96, 3), uint8)");
  CHECK(env.action_space().describe() == "Box([-1.0 0.0 0.0], [1.0 1.0 1.0], (3,), float32)");
  CarRacing::Config discrete;
  discrete.continuous = false;
  CHECK(CarRacing(discrete).action_space().describe() == "Discrete(5)");
  const EnvEntry* entry = builtin_registry().find_env("CarRacing-v3");
  REQUIRE(entry != nullptr);
  CHECK(entry->max_episode_steps == 1000);
  std::vector<std::string> keys;
  for (const auto& row : entry->params()) keys.push_back(row.key);
  CHECK(keys == std::vector<std::string>{"continuous", "domain_randomize", "lap_complete_percent"});
  REQUIRE(entry->policies.size() == 1);
  CHECK(entry->policies[0].name == "line-follower");
  CarRacing::Config bad;
  bad.lap_complete_percent = 1.5;
  CHECK_THROWS_AS(CarRacing(bad), std::invalid_argument);
  CHECK(env.render_spec().width == 600);
  CHECK(env.render_spec().height == 400);
  CHECK(env.render_spec().fps == 50);
}

TEST_CASE("car racing: generated tracks are closed loops of equal steps", "[car_racing]") {
  for (uint64_t seed = 0; seed < 20; ++seed) {
    Rng rng(seed);
    std::optional<std::vector<TrackPoint>> track;
    int attempts = 0;
    while (!track) {
      track = generate_track(rng);
      REQUIRE(++attempts < 50);
    }
    INFO("seed " << seed << ", " << track->size() << " points");
    // A morphed circle of radius TRACK_RAD (150) drawn at 3.5 m steps: 200 to 450 tiles.
    CHECK(track->size() > 200);
    CHECK(track->size() < 450);
    const auto& t = *track;
    for (size_t i = 0; i + 1 < t.size(); ++i) {
      // Every step moves TRACK_DETAIL_STEP along the heading beta had before its turn.
      REQUIRE(std::hypot(t[i + 1].x - t[i].x, t[i + 1].y - t[i].y) ==
              Approx(kTrackDetailStep).epsilon(1e-9));
      // The heading turns at most TRACK_TURN_RATE a step (beta is the mean of two headings).
      REQUIRE(std::abs(std::remainder(t[i + 1].beta - t[i].beta, 2 * std::numbers::pi)) <=
              kTrackTurnRate + 1e-9);
      REQUIRE(std::abs(t[i].x) < kPlayfield);
      REQUIRE(std::abs(t[i].y) < kPlayfield);
    }
    // Glued: the last point is about one step behind the first (across the heading at most one
    // step), and the start lies just past start_alpha = -pi/12.
    CHECK(std::hypot(t.back().x - t.front().x, t.back().y - t.front().y) < 4 * kTrackDetailStep);
    CHECK(std::atan2(t.front().y, t.front().x) > -std::numbers::pi / 12 - 0.1);
    CHECK(std::atan2(t.front().y, t.front().x) < 0.0);
  }
}

TEST_CASE("car racing: the road joins its tiles and marks hard turns", "[car_racing]") {
  Rng rng(7);
  std::optional<std::vector<TrackPoint>> track;
  while (!track) track = generate_track(rng);
  const Road road = build_road(*track);
  REQUIRE(road.tiles.size() == track->size());
  for (size_t i = 0; i < road.tiles.size(); ++i) {
    const Quad& tile = road.tiles[i];
    const Quad& next = road.tiles[(i + 1) % road.tiles.size()];
    // Tile i ends where tile i + 1 begins (its road1 edge is the next tile's road2 edge).
    CHECK(next[3] == tile[0]);
    CHECK(next[2] == tile[1]);
    // The road is 2 TRACK_WIDTH wide, centred on the track point.
    CHECK(std::hypot(tile[1][0] - tile[0][0], tile[1][1] - tile[0][1]) == Approx(2 * kTrackWidth));
    CHECK((tile[0][0] + tile[1][0]) / 2 == Approx((*track)[i].x));
  }
  // Kerbs lie on the outside edge of sharp turns, BORDER wide, alternating white and red.
  REQUIRE(!road.kerbs.empty());
  for (const RoadKerb& kerb : road.kerbs) {
    CHECK(std::hypot(kerb.quad[1][0] - kerb.quad[0][0], kerb.quad[1][1] - kerb.quad[0][1]) ==
          Approx(kBorder));
    CHECK(kerb.red == (kerb.tile % 2 == 1));
    const Quad& tile = road.tiles[kerb.tile];
    const bool on_left = kerb.quad[0] == tile[0], on_right = kerb.quad[0] == tile[1];
    CHECK((on_left || on_right));
  }
  // A straight track has none.
  CHECK(build_road(straight_track(0, 0, 30)).kerbs.empty());
}

TEST_CASE("car racing: a seed fixes the track and the pictures", "[car_racing]") {
  CarRacing a, b;
  Vec oa(kObsSize), ob(kObsSize);
  a.reset(11, oa);
  b.reset(11, ob);
  CHECK(oa == ob);
  REQUIRE(a.track().size() == b.track().size());
  for (int t = 0; t < 60; ++t) {
    drive(a, 0.3f, 0.5f, 0.0f, oa);
    drive(b, 0.3f, 0.5f, 0.0f, ob);
    REQUIRE(oa == ob);
  }
  a.reset(12, oa);
  CHECK(a.track().size() != b.track().size());
}

TEST_CASE("car racing: gas drives the rear wheels, brakes stop them, steering turns the front",
          "[car_racing]") {
  CarRacing env;
  Vec obs(kObsSize);
  env.set_next_track(straight_track(0, -150, 90));
  env.reset(0, obs);
  // The reset step: at rest, no controls, the first tiles visited but not paid yet.
  CarState car = env.car();
  CHECK(speed(car) < 0.1);
  CHECK(env.time() == Approx(1.0 / 50));
  for (const WheelState& w : car.wheels) CHECK(w.tiles > 0);

  // Gas rises by at most 0.1 a step on the rear wheels only; each wheel's omega grows by
  // dt * ENGINE_POWER * gas / WHEEL_MOMENT_OF_INERTIA / (|omega| + 5) before friction.
  drive(env, 0.0f, 1.0f, 0.0f, obs);
  car = env.car();
  CHECK(car.wheels[2].gas == Approx(0.1));
  CHECK(car.wheels[3].gas == Approx(0.1));
  CHECK(car.wheels[0].gas == 0.0);
  for (int t = 0; t < 20; ++t) drive(env, 0.0f, 1.0f, 0.0f, obs);
  car = env.car();
  CHECK(car.wheels[2].gas == Approx(1.0));
  CHECK(car.wheels[2].omega > 10);
  CHECK(car.wheels[0].omega > 0);  // the front wheels roll along
  // Forward is the hull's +y, here world +y.
  CHECK(car.hull.linear_velocity[1] > 3);
  CHECK(std::abs(car.hull.linear_velocity[0]) < 0.5);
  const double before = car.hull.position[1];
  for (int t = 0; t < 30; ++t) drive(env, 0.0f, 1.0f, 0.0f, obs);
  CHECK(env.car().hull.position[1] > before + 5);

  // brake >= 0.9 locks every wheel (omega = 0 before friction spins it a little again);
  // a weaker brake takes 15 * brake rad/s off per step.
  const double omega = env.car().wheels[0].omega;
  drive(env, 0.0f, 0.0f, 1.0f, obs);
  car = env.car();
  for (const WheelState& w : car.wheels) {
    CHECK(w.brake == 1.0);
    CHECK(std::abs(w.omega) < 0.2 * omega);
  }
  const double v0 = speed(env.car());
  for (int t = 0; t < 25; ++t) drive(env, 0.0f, 0.0f, 1.0f, obs);
  CHECK(speed(env.car()) < v0 - 5);

  // Steering: the front joints turn towards -action[0], at most 3 rad/s, within +-0.4 rad;
  // action[0] < 0 is a left turn (the heading grows).
  const double angle = env.car().hull.angle;
  for (int t = 0; t < 3; ++t) drive(env, -1.0f, 0.3f, 0.0f, obs);
  car = env.car();
  CHECK(car.wheels[0].steer == 1.0);
  CHECK(car.wheels[0].joint_angle > 0.05);
  CHECK(car.wheels[0].joint_angle <= 3.0 * 3 / 50 + 0.02);
  for (int t = 0; t < 30; ++t) drive(env, -1.0f, 0.3f, 0.0f, obs);
  car = env.car();
  CHECK(car.wheels[0].joint_angle == Approx(0.4).margin(0.03));
  CHECK(car.wheels[2].joint_angle == Approx(0.0).margin(0.03));  // rear wheels do not steer
  CHECK(car.hull.angle > angle + 0.1);
}

TEST_CASE("car racing: wheels off the road lose their tiles (grass grip)", "[car_racing]") {
  // Grip is FRICTION_LIMIT on a tile and 0.6 of it on grass: a wheel's tile set, kept by the
  // contact listener, decides. Steering hard left off a straight road empties every set.
  CarRacing env;
  Vec obs(kObsSize);
  env.set_next_track(straight_track(0, -150, 90));
  env.reset(0, obs);
  for (const WheelState& w : env.car().wheels) CHECK(w.tiles > 0);
  int off_road_steps = 0;
  for (int t = 0; t < 300 && off_road_steps < 5; ++t) {
    drive(env, -1.0f, 0.4f, 0.0f, obs);
    int tiles = 0;
    for (const WheelState& w : env.car().wheels) tiles += w.tiles;
    if (tiles == 0) ++off_road_steps;
  }
  CHECK(off_road_steps == 5);
  CHECK(std::abs(env.car().hull.position[0]) > kTrackWidth);
}

TEST_CASE("car racing: tiles pay 1000/N once, -0.1 a frame, a full lap ends the episode",
          "[car_racing]") {
  CarRacing env;
  Vec obs(kObsSize);
  env.reset(3, obs);
  const double n = static_cast<double>(env.track().size());
  // reset() pays nothing, though its step already visits the tiles under the car.
  const int at_start = env.tiles_visited();
  CHECK(at_start >= 1);
  CHECK(env.episode_reward() == Approx(1000.0 / n * at_start));
  double total = 0;
  int steps = 0;
  StepResult r;
  for (; steps < 1000; ++steps) {
    const auto c = line_follower_controls(env.car(), env.track());
    r = drive(env, c[0], c[1], c[2], obs);
    total += r.reward;
    // The sum of step rewards is Gymnasium's env.reward: tiles paid minus 0.1 a frame.
    REQUIRE(total == Approx(1000.0 / n * env.tiles_visited() - 0.1 * (steps + 1)).margin(1e-6));
    if (r.terminated) break;
  }
  // The scripted driver finishes a lap: every tile visited (tile 0 was visited at the start,
  // so the lap ends by the count, not by coming back to tile 0), lap_finished set.
  REQUIRE(r.terminated);
  CHECK(env.tiles_visited() == static_cast<int>(n));
  CHECK(env.info().get(env.info().find("lap_finished")) == 1.0);
  CHECK(total == Approx(1000 - 0.1 * (steps + 1)));
  CHECK(total > 880);  // Gymnasium's reward threshold is 900
}

TEST_CASE("car racing: leaving the playfield costs 100 and ends the episode", "[car_racing]") {
  CarRacing env;
  Vec obs(kObsSize);
  // A road whose first 12 tiles end 20 m before the playfield's edge (|y| <= 2000 / 6), then
  // goes on far away (so the lap is not over when the car runs off its end at full gas).
  std::vector<TrackPoint> track = straight_track(0, kPlayfield - 60, 12);
  for (int i = 0; i < 50; ++i) track.push_back({0, 0, -200, -100 + i * kTrackDetailStep});
  env.set_next_track(track);
  env.reset(0, obs);
  StepResult r;
  int t = 0;
  for (; t < 400 && !r.terminated; ++t) r = drive(env, 0.0f, 1.0f, 0.0f, obs);
  REQUIRE(r.terminated);
  CHECK(r.reward == -100);
  CHECK(env.car().hull.position[1] > kPlayfield);
  CHECK(env.info().get(env.info().find("lap_finished")) == 0.0);
}

TEST_CASE("car racing: a track set from outside is built, checked and used once", "[car_racing]") {
  CarRacing a, b;
  Vec oa(kObsSize), ob(kObsSize);
  a.reset(21, oa);
  const std::vector<TrackPoint> track(a.track().begin(), a.track().end());
  b.set_next_track(track);
  b.reset(99, ob);  // the seed does not change a set track
  CHECK(oa == ob);
  for (int t = 0; t < 40; ++t) {
    drive(a, 0.1f, 0.6f, 0.0f, oa);
    drive(b, 0.1f, 0.6f, 0.0f, ob);
  }
  CHECK(oa == ob);
  CHECK(a.car().hull.position == b.car().hull.position);
  b.reset(99, ob);  // the next reset generates again
  CHECK(b.track().size() != track.size());

  CHECK_THROWS_AS(b.set_next_track({{0, 0, 0, 0}, {0, 0, 1, 1}}), std::invalid_argument);
  CHECK_THROWS_AS(b.set_next_track(std::vector<TrackPoint>(5, TrackPoint{0, 0, 1, 1})),
                  std::invalid_argument);  // every tile degenerate
  std::vector<TrackPoint> far = straight_track(0, 0, 10);
  far[3].x = 1e6;
  CHECK_THROWS_AS(b.set_next_track(far), std::invalid_argument);
  far[3].x = NAN;
  CHECK_THROWS_AS(b.set_next_track(far), std::invalid_argument);
}

TEST_CASE("car racing: discrete actions are Gymnasium's five", "[car_racing]") {
  CarRacing::Config config;
  config.continuous = false;
  CarRacing env(config);
  Vec obs(kObsSize);
  env.set_next_track(straight_track(0, -150, 90));
  env.reset(0, obs);
  const auto act = [&](int a) {
    const float f = static_cast<float>(a);
    return env.step({&f, 1}, obs);
  };
  for (int t = 0; t < 5; ++t) act(3);  // gas: 0.2
  CHECK(env.car().wheels[2].gas == Approx(0.2));
  act(1);  // steer(-0.6)
  CHECK(env.car().wheels[0].steer == Approx(-0.6));
  act(2);
  CHECK(env.car().wheels[0].steer == Approx(0.6));
  act(4);  // brake 0.8, and the other controls back to 0
  CHECK(env.car().wheels[0].brake == Approx(0.8));
  CHECK(env.car().wheels[0].steer == 0.0);
  act(0);
  CHECK(env.car().wheels[0].brake == 0.0);
  const float bad = 5.0f;
  CHECK_THROWS(env.step({&bad, 1}, obs));
  CarRacing continuous;
  continuous.reset(0, obs);
  const float nan_action[3] = {NAN, 0, 0};
  CHECK_THROWS_AS(continuous.step({nan_action, 3}, obs), std::invalid_argument);
}

TEST_CASE("car racing: domain_randomize draws colours per reset unless told not to",
          "[car_racing]") {
  CarRacing::Config config;
  config.domain_randomize = true;
  CarRacing env(config);
  Vec obs(kObsSize);
  env.reset(1, obs);
  const CarRacingColors first = env.colors();
  CHECK(first.road != CarRacingColors{}.road);
  for (int c = 0; c < 3; ++c) {
    CHECK(first.road[c] >= 0);
    CHECK(first.road[c] < 210);
  }
  int raised = 0;  // the grass is the background plus 20 in one channel
  for (int c = 0; c < 3; ++c) raised += first.grass[c] == first.bg[c] + 20 ? 1 : 0;
  CHECK(raised == 1);
  env.reset(std::nullopt, obs);
  CHECK(env.colors().road != first.road);
  const CarRacingColors second = env.colors();
  env.set_next_randomize(false);
  env.reset(std::nullopt, obs);
  CHECK(env.colors().road == second.road);
  CarRacing plain;
  plain.reset(1, obs);
  CHECK(plain.colors().road == CarRacingColors{}.road);
}

TEST_CASE("car racing: the observation shows the car, the road and the indicator bar",
          "[car_racing][render]") {
  CarRacing env;
  Vec obs(kObsSize);
  env.reset(5, obs);
  // The first picture is zoomed out (0.91 px per metre in the window): the whole playfield.
  int road = 0, grass = 0;
  const auto count = [&](const Vec& o) {
    road = grass = 0;
    for (int y = 0; y < 84; ++y)
      for (int x = 0; x < 96; ++x) {
        const auto p = pixel(o, x, y);
        road += p[0] >= 100 && p[0] <= 110 && p[0] == p[1] && p[1] == p[2];
        grass += p[0] == 102 && (p[1] == 204 || p[1] == 230) && p[2] == 102;
      }
  };
  count(obs);
  CHECK(grass > 1000);
  CHECK(road > 20);
  CHECK(road < 800);
  for (int t = 0; t < 60; ++t) drive(env, 0.0f, 0.0f, 0.0f, obs);  // zoomed in after 1 s
  count(obs);
  CHECK(road > 1000);
  // The car (red hull (204, 0, 0)) sits centred at 3/4 of the window's height (y = 72 of 96).
  int red = 0;
  for (int y = 60; y < 84; ++y)
    for (int x = 40; x < 56; ++x) {
      const auto p = pixel(obs, x, y);
      red += p[0] > 150 && p[1] < 60 && p[2] < 60;
    }
  CHECK(red >= 3);
  // The bottom 5/40 (12 rows) is the black indicator bar; the car stands still, so only the
  // reward counter's white digits light its left end.
  for (int y = 84; y < 96; ++y)
    for (int x = 20; x < 96; ++x) REQUIRE(pixel(obs, x, y) == std::array<uint8_t, 3>{0, 0, 0});
  int lit = 0;
  for (int y = 84; y < 96; ++y)
    for (int x = 0; x < 14; ++x) lit += pixel(obs, x, y)[0] > 60;
  CHECK(lit > 5);
  // With gas, the speed (white) and wheel-spin (blue) bars appear.
  for (int t = 0; t < 20; ++t) drive(env, 0.0f, 1.0f, 0.0f, obs);
  int blue = 0;
  for (int y = 84; y < 96; ++y)
    for (int x = 16; x < 27; ++x) blue += pixel(obs, x, y)[2] > 60 && pixel(obs, x, y)[0] < 60;
  CHECK(blue > 0);

  Frame frame(600, 400);
  REQUIRE(env.render(frame));
  CHECK(frame.pixel(300, 390) == Rgb{0, 0, 0});
  CHECK(frame.pixel(300, 300).r > 150);  // the hull at (W/2, 3H/4)
}

TEST_CASE("car racing: env checker and the line follower through the CLI",
          "[car_racing][env_checker][cli]") {
  for (const bool continuous : {true, false}) {
    CarRacing::Config config;
    config.continuous = continuous;
    TimeLimit env(std::make_unique<CarRacing>(config), CarRacing::kMaxEpisodeSteps);
    const auto problems = check_env(env, 0, 200);
    std::string all;
    for (const auto& p : problems) all += p + "\n";
    INFO(all);
    CHECK(problems.empty());
  }
  TempDir dir("car_racing_cli");
  const auto r = run_rlrun("eval --env CarRacing-v3 --policy line-follower --episodes 1 --seed 3");
  INFO(r.output);
  REQUIRE(r.exit_code == 0);
  CHECK(r.output.find("line-follower on CarRacing-v3, 1 episode") != std::string::npos);
  const auto video = run_rlrun("record --env CarRacing-v3 --policy random --episodes 1 --output " +
                               dir / "car.mp4");
  INFO(video.output);
  REQUIRE(video.exit_code == 0);
  CHECK(probe_video(dir / "car.mp4").find("h264,600,400,1001") != std::string::npos);
}

// Env steps per second on one core (each step draws the 96x96 observation), random actions.
// Measured, not asserted (docs/benchmarks.md): `build/tests/rlrun_tests "[car_racing_bench]"`.
TEST_CASE("bench: CarRacing-v3 env steps/s", "[.bench][car_racing_bench]") {
  CarRacing env;
  Vec obs(kObsSize);
  Rng actions(1);
  constexpr int kSteps = 20000;
  const auto start = std::chrono::steady_clock::now();
  env.reset(1, obs);
  for (int i = 0, since_reset = 0; i < kSteps; ++i) {
    float a[3];
    env.action_space().sample(actions, a);
    const auto r = env.step({a, 3}, obs);
    if (r.terminated || ++since_reset == CarRacing::kMaxEpisodeSteps) {
      env.reset(std::nullopt, obs);
      since_reset = 0;
    }
  }
  const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::printf("| CarRacing-v3, random actions, one core | %.0f steps/s |\n", kSteps / s);
}
