// BipedalWalker-v3 / BipedalWalkerHardcore-v3 (gymnasium/envs/box2d/bipedal_walker.py on
// Box2D 2.4): spaces, seeding, the terrain rules, the lidar against geometry, leg contacts,
// the reward decomposition, falling, Gymnasium's scripted walker, time limits and `record`.
// The speed is a hidden bench case ([walker_bench]).
#include <catch2/catch.hpp>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <regex>
#include <vector>

#include "rlrun/core/errors.hpp"
#include "rlrun/envs/bipedal_walker/bipedal_walker.hpp"
#include "rlrun/envs/bipedal_walker/walking_heuristic.hpp"
#include "rlrun/frame.hpp"
#include "rlrun/rng.hpp"
#include "rlrun/runtime/components/builtins.hpp"
#include "rlrun/runtime/experiment/env_factory.hpp"
#include "runtime/cli_runner.hpp"
#include "runtime/video_probe.hpp"

using namespace rlrun;
using namespace rlrun::testing;
using namespace rlrun::walker;

namespace {

using Obs = std::vector<float>;

struct Episode {
  double total = 0;
  int steps = 0;
  bool terminated = false;
  double final_x = 0;
  StepResult last;
};

// One episode of at most `max_steps` steps: zero actions, or Gymnasium's scripted gait run as
// its __main__ runs it (a = 0 first, then the heuristic of each new observation).
Episode run(BipedalWalker& env, uint64_t seed, int max_steps, bool heuristic) {
  Obs obs(kObsSize);
  env.reset(seed, obs);
  WalkingHeuristic gait;
  Episode e;
  std::array<float, 4> a{};
  while (e.steps < max_steps) {
    e.last = env.step(a, obs);
    e.total += e.last.reward;
    ++e.steps;
    if (e.last.terminated) {
      e.terminated = true;
      break;
    }
    if (heuristic) a = gait.act(obs);
  }
  e.final_x = env.hull_position().x;
  return e;
}

}  // namespace

TEST_CASE("BipedalWalker: Gymnasium's ids, spaces, kwargs and time limits", "[walker]") {
  BipedalWalker env;
  CHECK(env.id() == "BipedalWalker-v3");
  CHECK(env.action_space().describe() == "Box(-1.0, 1.0, (4,), float32)");
  const float pi = static_cast<float>(M_PI);
  const std::vector<float> high{pi, 5, 5, 5, pi, 5, pi, 5, 5, pi, 5, pi,
                                5,  5, 1, 1, 1,  1, 1,  1, 1, 1,  1, 1};
  std::vector<float> low(high.size());
  for (size_t i = 0; i < high.size(); ++i) low[i] = -high[i];
  low[8] = low[13] = 0.0f;  // the contacts' lower bound is -0.0
  CHECK(env.observation_space().high() == high);
  CHECK(env.observation_space().low() == low);
  CHECK(env.observation_space().shape() == std::vector<int>{24});
  CHECK(env.render_spec().width == 600);
  CHECK(env.render_spec().height == 400);
  CHECK(env.render_spec().fps == 50);

  const Registry& registry = builtin_registry();
  const EnvEntry* normal = registry.find_env("BipedalWalker-v3");
  const EnvEntry* hard = registry.find_env("BipedalWalkerHardcore-v3");
  REQUIRE(normal);
  REQUIRE(hard);
  CHECK(normal->max_episode_steps == 1600);
  CHECK(hard->max_episode_steps == 2000);
  // The alias is the same class with hardcore on by default; BipedalWalker-v3 takes the kwarg.
  EnvPtr made = hard->make(hard->parse(ConfigNode{}));
  CHECK(dynamic_cast<BipedalWalker&>(*made).config().hardcore);
  CHECK(made->id() == "BipedalWalkerHardcore-v3");
  CHECK_FALSE(
      dynamic_cast<BipedalWalker&>(*normal->make(normal->parse(ConfigNode{}))).config().hardcore);
  REQUIRE(normal->policies.size() == 1);
  CHECK(normal->policies[0].name == "heuristic");
}

TEST_CASE("BipedalWalker: a seed fixes the terrain and the episode", "[walker]") {
  for (const bool hardcore : {false, true}) {
    BipedalWalker a(BipedalWalker::Config{hardcore}), b(BipedalWalker::Config{hardcore});
    Obs oa(kObsSize), ob(kObsSize);
    a.reset(7, oa);
    b.reset(7, ob);
    CHECK(oa == ob);
    CHECK(a.terrain().y == b.terrain().y);
    Rng actions(3);
    for (int t = 0; t < 300; ++t) {
      float act[4];
      a.action_space().sample(actions, act);
      const StepResult ra = a.step(act, oa), rb = b.step(act, ob);
      REQUIRE(oa == ob);
      REQUIRE(ra.reward == rb.reward);
      REQUIRE(ra.terminated == rb.terminated);
      if (ra.terminated) break;
    }
    b.reset(8, ob);
    CHECK(a.terrain().y != b.terrain().y);
    // No seed continues the stream: a second unseeded reset draws a new terrain.
    a.reset(7, oa);
    const auto first = a.terrain().y;
    a.reset(std::nullopt, oa);
    CHECK(a.terrain().y != first);
  }
}

TEST_CASE("BipedalWalker: the terrain follows Gymnasium's generator", "[walker]") {
  for (uint64_t seed = 0; seed < 20; ++seed) {
    Rng rng(seed);
    const Terrain t = generate_terrain(rng, false);
    REQUIRE(t.x.size() == 200);
    REQUIRE(t.y.size() == 200);
    CHECK(t.obstacles.empty());
    CHECK(t.clouds.size() == 10);
    for (int i = 0; i <= kTerrainStartpad; ++i) CHECK(t.y[i] == kTerrainHeight);  // start pad
    CHECK(t.y[kTerrainStartpad + 1] != kTerrainHeight);
    CHECK(t.x[199] == Approx(199 * 14 / 30.0));
    // The grass velocity is pulled toward TERRAIN_HEIGHT: the ground stays near it.
    for (const double y : t.y) CHECK(std::abs(y - kTerrainHeight) < 5.0);
  }
  int stumps = 0, stairs = 0, pits = 0;
  for (uint64_t seed = 0; seed < 20; ++seed) {
    Rng rng(seed);
    const Terrain t = generate_terrain(rng, true);
    for (int i = 0; i <= kTerrainStartpad; ++i) CHECK(t.y[i] == kTerrainHeight);
    REQUIRE_FALSE(t.obstacles.empty());
    for (const Obstacle& o : t.obstacles) {
      const double w = o.corners[1].x - o.corners[0].x;
      CHECK(o.corners[0].x > kTerrainStartpad * kTerrainStep - 1e-9);  // after the start pad
      switch (o.kind) {
        case ObstacleKind::kStump: {  // a square of 1 or 2 steps on the ground
          ++stumps;
          const double h = o.corners[2].y - o.corners[1].y;
          CHECK(w == Approx(h));
          CHECK((w == Approx(kTerrainStep) || w == Approx(2 * kTerrainStep)));
          break;
        }
        case ObstacleKind::kStairs:  // steps 4 wide, 1 high
          ++stairs;
          CHECK(w == Approx(4 * kTerrainStep));
          CHECK(o.corners[1].y - o.corners[2].y == Approx(kTerrainStep));
          break;
        case ObstacleKind::kPit:  // walls 1 wide, 4 deep
          ++pits;
          CHECK(w == Approx(kTerrainStep));
          CHECK(o.corners[1].y - o.corners[2].y == Approx(4 * kTerrainStep));
          break;
      }
    }
  }
  CHECK(stumps > 10);
  CHECK(stairs > 20);
  CHECK(pits > 10);
  CHECK(pits % 2 == 0);  // each pit has two walls
  // A pit's floor is 4 steps below its rim between its walls.
  int pit_floors = 0;
  for (uint64_t seed = 0; seed < 10; ++seed) {
    Rng rng(seed);
    const Terrain t = generate_terrain(rng, true);
    for (size_t k = 0; k + 1 < t.obstacles.size(); ++k) {
      if (t.obstacles[k].kind != ObstacleKind::kPit) continue;
      const double rim = t.obstacles[k].corners[0].y;
      const auto i = static_cast<size_t>(std::lround(t.obstacles[k].corners[0].x / kTerrainStep));
      CHECK(t.y[i + 2] == Approx(rim - 4 * kTerrainStep));
      ++pit_floors;
      ++k;  // the pit's second wall
    }
  }
  CHECK(pit_floors > 0);
}

TEST_CASE("BipedalWalker: lidar fractions on the flat start pad match the geometry", "[walker]") {
  for (const uint64_t seed : {0, 1, 2, 3}) {
    BipedalWalker env;
    Obs obs(kObsSize);
    env.reset(seed, obs);
    for (int t = 0; t < 5; ++t) env.step(std::array<float, 4>{}, obs);
    const b2Vec2 p = env.hull_position();
    const double height = p.y - kTerrainHeight;  // the hull origin above the flat ground
    REQUIRE(height > 0.5);
    int checked = 0;
    for (int i = 0; i < kLidarRays; ++i) {
      const double theta = 1.5 * i / 10.0;
      const double expected = height / std::cos(theta) / kLidarRange;
      const double hit_x = p.x + height * std::tan(theta);
      const auto [p1, p2] = env.lidar_ray(i);
      CHECK(p1.x == p.x);
      if (expected < 1.0 && hit_x < kTerrainStartpad * kTerrainStep - 0.05) {
        INFO("seed " << seed << " ray " << i);
        CHECK(obs[14 + i] == Approx(expected).margin(2e-5));
        CHECK(p2.y == Approx(kTerrainHeight).margin(1e-4));
        ++checked;
      } else {
        CHECK(obs[14 + i] <= 1.0f);
      }
    }
    CHECK(checked >= 5);  // rays 0..4 at least reach the pad
  }
}

TEST_CASE("BipedalWalker: the feet land, with the motors off the walker collapses", "[walker]") {
  // Gymnasium's reset builds each leg LEG_H / 2 + LEG_DOWN above its hip anchor; the joint
  // solver pulls them together in the reset's own step, so the feet stand on the pad at once.
  // With every motor off (maxMotorTorque 0) the joints then fold freely within their limits
  // until the hull hits the ground: game over, -100, terminated.
  for (const uint64_t seed : {0, 1, 2}) {
    BipedalWalker env;
    Obs obs(kObsSize);
    env.reset(seed, obs);
    int landed = -1;
    const std::array<float, 4> off{};
    StepResult r;
    int t = 0;
    for (; t < 400; ++t) {
      r = env.step(off, obs);
      if (landed < 0 && obs[8] == 1.0f && obs[13] == 1.0f) landed = t;
      if (r.terminated) break;
      CHECK(r.reward > -1.0);  // small shaping changes while it sinks
      CHECK_FALSE(env.game_over());
      // The joints stay inside their limits (Box2D allows a little slop).
      CHECK(obs[4] > -0.8f - 0.05f);
      CHECK(obs[4] < 1.1f + 0.05f);
      CHECK(obs[6] - 1.0f > -1.6f - 0.05f);
      CHECK(obs[6] - 1.0f < -0.1f + 0.05f);
    }
    INFO("seed " << seed << ": landed at step " << landed << ", hull down at step " << t);
    CHECK(landed >= 0);
    CHECK(landed < 20);
    REQUIRE(r.terminated);
    CHECK(env.game_over());
    CHECK(r.reward == -100.0);
    CHECK(t > 50);  // folding takes time
    CHECK(std::abs(env.hull_position().x - kTerrainStep * kTerrainStartpad / 2) < 3.0);
  }
}

TEST_CASE("BipedalWalker: reward = shaping difference - 0.00035 * 80 * sum |a|", "[walker]") {
  BipedalWalker env;
  Obs obs(kObsSize);
  env.reset(5, obs);
  Rng actions(11);
  for (int t = 0; t < 60; ++t) {
    // Actions beyond the box are clipped for the cost (np.clip(np.abs(a), 0, 1)).
    float a[4];
    for (float& v : a) v = static_cast<float>(actions.uniform(-1.3, 1.3));
    const double before = env.shaping();
    const StepResult r = env.step(a, obs);
    if (r.terminated) break;
    double cost = 0;
    for (const float v : a) cost += 0.00035 * 80 * std::min(1.0, std::abs(double{v}));
    const double shaping = 130 * env.hull_position().x / 30.0 - 5 * std::abs(double{obs[0]});
    CHECK(env.shaping() == Approx(shaping).epsilon(1e-12));
    CHECK(r.reward == Approx(shaping - before - cost).epsilon(1e-9).margin(1e-12));
  }
}

TEST_CASE("BipedalWalker: a fall costs -100 and terminates, contacts reach the observation",
          "[walker]") {
  // Random flailing brings the hull down (game over) within a few episodes.
  BipedalWalker env;
  Obs obs(kObsSize);
  Rng actions(1);
  int falls = 0;
  bool saw_contact[2] = {false, false};
  for (uint64_t episode = 0; episode < 10; ++episode) {
    env.reset(episode, obs);
    for (int t = 0; t < 400; ++t) {
      float a[4];
      env.action_space().sample(actions, a);
      const StepResult r = env.step(a, obs);
      for (int leg = 0; leg < 2; ++leg) {
        CHECK(obs[8 + 5 * leg] == (env.leg_contact(2 * leg + 1) ? 1.0f : 0.0f));
        saw_contact[leg] |= obs[8 + 5 * leg] == 1.0f;
      }
      CHECK(env.observation_space().contains(obs));
      if (r.terminated) {
        CHECK(env.game_over());
        CHECK(r.reward == -100.0);
        ++falls;
        break;
      }
      CHECK_FALSE(env.game_over());
    }
  }
  CHECK(falls >= 3);
  CHECK(saw_contact[0]);
  CHECK(saw_contact[1]);
}

TEST_CASE("BipedalWalker: Gymnasium's scripted gait walks as it does in Gymnasium", "[walker]") {
  // Reference: EnvPool's Box2D test (envpool/box2d/box2d_correctness_test.py) quotes the
  // heuristic's mean return over 1000 episodes of Gym's own env: 102.65 +/- 125.08 (normal)
  // and -59.22 +/- 25.21 (hardcore). Over 100 episodes the mean must lie within 3 standard
  // errors of it.
  for (const bool hardcore : {false, true}) {
    const double reference = hardcore ? -59.22 : 102.65;
    const double std_error = (hardcore ? 25.21 : 125.08) / 10.0;
    const int limit = hardcore ? kMaxEpisodeStepsHardcore : kMaxEpisodeSteps;
    BipedalWalker env(BipedalWalker::Config{hardcore});
    double sum = 0, furthest = 0;
    int finished = 0;
    for (uint64_t seed = 0; seed < 100; ++seed) {
      const Episode e = run(env, seed, limit, true);
      sum += e.total;
      furthest = std::max(furthest, e.final_x);
      finished += e.terminated && !env.game_over();
    }
    const double mean = sum / 100;
    INFO((hardcore ? "hardcore" : "normal")
         << ": mean return " << mean << ", " << finished << " of 100 reached the end");
    CHECK(std::abs(mean - reference) < 3 * std_error);
    if (!hardcore) {
      CHECK(finished >= 5);  // walks the whole course (x > 88.7 m) in some episodes
      CHECK(furthest > (kTerrainLength - kTerrainGrass) * kTerrainStep);
    }
  }
  // It walks forward from the first steps on: 300 steps carry the hull well ahead.
  for (const uint64_t seed : {0, 1, 2}) {
    BipedalWalker env;
    const Episode e = run(env, seed, 300, true);
    INFO("seed " << seed << ": x " << e.final_x << ", return " << e.total);
    CHECK(e.final_x > 10.0);
    CHECK(e.total > 20.0);
  }
}

TEST_CASE("BipedalWalker: make_env adds the registered time limit", "[walker]") {
  // The heuristic neither falls nor finishes in some episodes: TimeLimit ends them at 1600.
  EnvSpec spec;
  spec.id = "BipedalWalker-v3";
  EnvPtr env = make_env(spec, builtin_registry(), "", 0.0);
  int truncated = 0;
  for (uint64_t seed = 0; seed < 40 && truncated == 0; ++seed) {
    Obs obs(kObsSize);
    env->reset(seed, obs);
    WalkingHeuristic gait;
    std::array<float, 4> a{};
    StepResult r;
    int steps = 0;
    do {
      r = env->step(a, obs);
      a = gait.act(obs);
      ++steps;
    } while (!r.terminated && !r.truncated);
    CHECK(steps <= 1600);
    if (r.truncated) {
      CHECK(steps == 1600);
      CHECK_FALSE(r.terminated);
      ++truncated;
    }
  }
  CHECK(truncated == 1);
}

TEST_CASE("BipedalWalker: render draws Gymnasium's picture", "[walker][render]") {
  BipedalWalker env(BipedalWalker::Config{true});
  Obs obs(kObsSize);
  env.reset(0, obs);
  Frame frame(600, 400);
  REQUIRE(env.render(frame));
  // Sky (and white clouds) above, the green ground below.
  int sky = 0, clouds = 0, ground = 0;
  for (int x = 0; x < 600; ++x) {
    sky += frame.pixel(x, 150) == Rgb{215, 215, 255};
    clouds += frame.pixel(x, 150) == Rgb{255, 255, 255};
    ground += frame.pixel(x, 395) == Rgb{102, 153, 76};
  }
  CHECK(sky > 200);
  CHECK(sky + clouds > 580);
  CHECK(ground == 600);
  // The hull (x 4.67 m, 0.67 m right of the window's left edge) in its colour.
  const b2Vec2 p = env.hull_position();
  const double left = (p.x - 4.0) * 30;
  const int hx = static_cast<int>(p.x * 30 - left), hy = static_cast<int>(400 - p.y * 30);
  CHECK(frame.pixel(hx, hy) == Rgb{127, 51, 229});
}

TEST_CASE("eval and record --policy heuristic on BipedalWalker", "[walker][cli]") {
  TempDir dir("walker_cli");
  const auto r = run_rlrun("eval --env BipedalWalker-v3 --policy heuristic --episodes 2");
  INFO(r.output);
  REQUIRE(r.exit_code == 0);
  CHECK(r.output.find("heuristic on BipedalWalker-v3, 2 episodes") != std::string::npos);
  const auto video =
      run_rlrun("record --env BipedalWalkerHardcore-v3 --policy heuristic --output " +
                dir / "walker.mp4" + " --frames " + dir / "frames");
  INFO(video.output);
  REQUIRE(video.exit_code == 0);
  std::smatch m;
  REQUIRE(std::regex_search(video.output, m, std::regex(R"((\d+) frames at 600x400, 50 fps)")));
  CHECK(probe_video(dir / "walker.mp4").find("h264,600,400," + m[1].str()) != std::string::npos);
  CHECK(std::filesystem::exists(dir / "frames/frame_000001.png"));
}

// Steps per second of wall time and of this process's CPU time (the machine may be shared:
// CPU time is what one core delivers). Measured, not asserted (docs/benchmarks.md).
TEST_CASE("bench: BipedalWalker-v3 env steps/s", "[.bench][walker_bench]") {
  std::printf("| run | steps/s (wall) | steps/s (CPU) |\n|---|---|---|\n");
  for (const bool hardcore : {false, true}) {
    BipedalWalker env(BipedalWalker::Config{hardcore});
    for (const bool heuristic : {false, true}) {
      Obs obs(kObsSize);
      Rng actions(1);
      WalkingHeuristic gait;
      constexpr int kSteps = 20000;
      int resets = 1;
      const auto start = std::chrono::steady_clock::now();
      const std::clock_t cpu_start = std::clock();
      env.reset(1, obs);
      std::array<float, 4> a{};
      for (int i = 0; i < kSteps; ++i) {
        if (heuristic)
          a = gait.act(obs);
        else
          env.action_space().sample(actions, a);
        if (env.step(a, obs).terminated) {  // resets (a new world each) included
          env.reset(std::nullopt, obs);
          gait.restart();
          ++resets;
        }
      }
      const double wall =
          std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      const double cpu = static_cast<double>(std::clock() - cpu_start) / CLOCKS_PER_SEC;
      std::printf("| %s, %s, one core (%d episodes) | %.0f | %.0f |\n", env.id().c_str(),
                  heuristic ? "heuristic gait" : "random actions", resets, kSteps / wall,
                  kSteps / cpu);
    }
  }
}
