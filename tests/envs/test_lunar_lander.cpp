// LunarLander-v3's rules (gymnasium/envs/box2d/lunar_lander.py,
// Gymnasium 1.0.0) on Box2D 2.4: spaces and registration, seeding, the
// unpowered drop, fuel costs by reward decomposition, leg contacts, wind,
// continuous throttles, Gymnasium's heuristic landing, the env checker, drawing
// and the CLI (eval / record --policy heuristic). The step-rate bench is
// hidden.
#include <catch2/catch.hpp>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <numeric>
#include <regex>
#include <string>
#include <vector>

#include "rlrun/env/env_checker.hpp"
#include "rlrun/envs/lunar_lander/heuristic_policy.hpp"
#include "rlrun/envs/lunar_lander/lunar_lander.hpp"
#include "rlrun/frame.hpp"
#include "rlrun/runtime/components/builtins.hpp"
#include "rlrun/wrappers/time_limit.hpp"
#include "runtime/cli_runner.hpp"
#include "runtime/video_probe.hpp"

using namespace rlrun;
using namespace rlrun::testing;

namespace {

using Vec = std::vector<float>;

StepResult act(LunarLander& env, int action, Vec& obs) {
  const float a = static_cast<float>(action);
  return env.step({&a, 1}, obs);
}

StepResult act(LunarLander& env, float main, float lateral, Vec& obs) {
  const float a[2] = {main, lateral};
  return env.step({a, 2}, obs);
}

// Gymnasium's shaping, from an observation (float32, so comparisons allow
// ~1e-4).
double shaping(const Vec& s) {
  return -100 * std::sqrt(double(s[0]) * s[0] + double(s[1]) * s[1]) -
         100 * std::sqrt(double(s[2]) * s[2] + double(s[3]) * s[3]) - 100 * std::abs(double(s[4])) +
         10 * double(s[6]) + 10 * double(s[7]);
}

LunarLander::Config continuous_config() {
  LunarLander::Config c;
  c.continuous = true;
  return c;
}

// One episode of Gymnasium's heuristic, to its end or the 1000-step limit.
double heuristic_return(LunarLander& env, uint64_t seed, int* steps = nullptr) {
  Vec obs(8);
  env.reset(seed, obs);
  double total = 0;
  for (int t = 0; t < LunarLander::kMaxEpisodeSteps; ++t) {
    const auto a = lunar_lander_heuristic(obs, env.config().continuous);
    const auto r =
        env.config().continuous ? act(env, a[0], a[1], obs) : act(env, static_cast<int>(a[0]), obs);
    total += r.reward;
    if (steps) *steps = t + 1;
    if (r.terminated) break;
  }
  return total;
}

}  // namespace

TEST_CASE("lunar lander: spaces, registration and kwargs", "[lunar_lander]") {
  LunarLander env;
  CHECK(env.id() == "LunarLander-v3");
  CHECK(env.action_space().describe() == "Discrete(4)");
  const Space& o = env.observation_space();
  REQUIRE(o.is_box());
  CHECK(o.flat_dim() == 8);
  // v3's bounds: +-2.5 positions, +-10 velocities, +-2 pi angle, legs 0..1.
  const std::vector<float> high = {2.5f,  2.5f, 10.0f, 10.0f, static_cast<float>(2 * M_PI),
                                   10.0f, 1.0f, 1.0f};
  for (int i = 0; i < 8; ++i) {
    CHECK(o.high()[i] == high[i]);
    CHECK(o.low()[i] == (i >= 6 ? 0.0f : -high[i]));
  }
  LunarLander continuous(continuous_config());
  CHECK(continuous.id() == "LunarLanderContinuous-v3");
  CHECK(continuous.action_space().describe() == "Box(-1.0, 1.0, (2,), float32)");

  for (const char* id : {"LunarLander-v3", "LunarLanderContinuous-v3"}) {
    const EnvEntry* entry = builtin_registry().find_env(id);
    REQUIRE(entry != nullptr);
    CHECK(entry->max_episode_steps == 1000);
    REQUIRE(entry->policies.size() == 1);
    CHECK(entry->policies[0].name == "heuristic");
    std::vector<std::string> keys;
    for (const auto& row : entry->params()) keys.push_back(row.key);
    CHECK(keys == std::vector<std::string>{"continuous", "gravity", "enable_wind", "wind_power",
                                           "turbulence_power"});
    // The alias differs only by the default of `continuous`; kwargs still
    // override it.
    const auto built = entry->build(entry->parse(ConfigNode{}), EnvContext{});
    CHECK(built->id() == id);
    CHECK(entry->params()[0].default_value ==
          (std::string(id) == "LunarLander-v3" ? "false" : "true"));
  }
  LunarLander::Config bad;
  for (double g : {-12.0, 0.0, 1.0, -20.0}) {
    bad.gravity = g;
    CHECK_THROWS_AS(LunarLander(bad), std::invalid_argument);
  }
  bad.gravity = -11.99;
  CHECK_NOTHROW(LunarLander(bad));
}

TEST_CASE("lunar lander: a seed fixes terrain, push and trajectory", "[lunar_lander]") {
  LunarLander a, b;
  Vec oa(8), ob(8);
  a.reset(42, oa);
  b.reset(42, ob);
  CHECK(oa == ob);
  CHECK(a.terrain_y() == b.terrain_y());
  // The lander starts at the top centre: x near 0, y = (H - (H/4 +
  // LEG_DOWN/SCALE)) / (H/2).
  CHECK(std::abs(oa[0]) < 0.02);
  CHECK(oa[1] ==
        Approx((400.0 / 30 - (400.0 / 30 / 4 + 18.0 / 30)) / (400.0 / 30 / 2)).margin(0.02));
  CHECK(oa[6] == 0.0f);
  CHECK(oa[7] == 0.0f);
  // The helipad: flat at H/4 between chunks 4 and 6.
  CHECK(a.helipad_x1() == Approx(8.0));
  CHECK(a.helipad_x2() == Approx(12.0));
  CHECK(a.helipad_y() == Approx(400.0 / 30 / 4));
  for (int i = 4; i <= 6; ++i) CHECK(a.terrain_y()[i] == Approx(0.99 * a.helipad_y()));
  for (int t = 0; t < 200; ++t) {
    const int action = t % 4;
    const auto ra = act(a, action, oa), rb = act(b, action, ob);
    REQUIRE(oa == ob);
    REQUIRE(ra.reward == rb.reward);
    if (ra.terminated) break;
  }
  // Another seed: another terrain and push; no seed continues the stream.
  b.reset(43, ob);
  CHECK(a.terrain_y() != b.terrain_y());
  a.reset(42, oa);
  const auto first = a.terrain_y();
  a.reset(std::nullopt, oa);
  CHECK(a.terrain_y() != first);
}

TEST_CASE("lunar lander: dropped without thrust it lands or crashes", "[lunar_lander]") {
  LunarLander env;
  Vec obs(8);
  int crashes = 0, rests = 0;
  for (uint64_t seed = 0; seed < 10; ++seed) {
    env.reset(seed, obs);
    bool legs_touched = false;
    int steps = 0;
    StepResult r;
    do {
      r = act(env, LunarLander::kNoop, obs);
      ++steps;
      legs_touched = legs_touched || obs[6] == 1.0f || obs[7] == 1.0f;
    } while (!r.terminated && steps < 1000);
    INFO("seed " << seed << " steps " << steps << " reward " << r.reward);
    REQUIRE(r.terminated);
    CHECK(steps < 1000);
    // The legs hang below the hull: they touch the ground before the hull does,
    // or at the latest within the same 20 ms step when the lander falls
    // straight at ~14 m/s.
    CHECK(legs_touched);
    if (r.reward == -100) {
      ++crashes;
      CHECK((env.game_over() || std::abs(obs[0]) >= 1.0f));
    } else {
      ++rests;
      CHECK(r.reward == 100);
      CHECK(!env.lander_awake());
    }
  }
  // Free fall from 13 m at g = -10 lands at ~14 m/s: the legs fold and the hull
  // hits the ground in Gymnasium, nearly always.
  CHECK(crashes >= 8);
  CHECK(crashes + rests == 10);
}

TEST_CASE(
    "lunar lander: fuel costs 0.3 per main-engine frame and 0.03 per "
    "side frame",
    "[lunar_lander]") {
  LunarLander env;
  Vec obs(8), prev(8);
  env.reset(5, obs);
  const double costs[4] = {0.0, 0.03, 0.3, 0.03};
  int checked = 0;
  for (int t = 0; t < 60; ++t) {
    const int action = (t / 3) % 4;
    prev = obs;
    const auto r = act(env, action, obs);
    if (r.terminated) break;
    CHECK(r.reward == Approx(shaping(obs) - shaping(prev) - costs[action]).margin(2e-3));
    CHECK(env.main_power() == (action == 2 ? 1.0 : 0.0));
    CHECK(env.side_power() == (action % 2 == 1 ? 1.0 : 0.0));
    ++checked;
  }
  CHECK(checked == 60);
  // The reset's own step has no previous shaping: its reward would be 0 (not
  // returned).
}

TEST_CASE("lunar lander: engines push the way Gymnasium's do", "[lunar_lander]") {
  // Main engine: decelerates the fall. The left engine (1) fires at the hull's
  // right side, above the centre of mass, pushing left: it turns the lander
  // anticlockwise (positive angle, what the heuristic asks for with angle_todo
  // > 0); the right engine (3) the opposite.
  Vec obs(8), base(8);
  LunarLander env;
  auto after = [&](int action, int steps) {
    env.reset(11, obs);
    for (int t = 0; t < steps; ++t) act(env, action, obs);
    return obs;
  };
  base = after(LunarLander::kNoop, 20);
  const Vec main = after(LunarLander::kMainEngine, 20);
  const Vec left = after(LunarLander::kLeftEngine, 20);
  const Vec right = after(LunarLander::kRightEngine, 20);
  CHECK(main[3] > base[3] + 0.2);
  CHECK(left[5] > base[5] + 0.05);
  CHECK(right[5] < base[5] - 0.05);
  CHECK(left[4] > base[4]);
  CHECK(right[4] < base[4]);
  CHECK(left[2] < base[2]);
  CHECK(right[2] > base[2]);
}

TEST_CASE("lunar lander: leg contact flags follow Box2D's contacts", "[lunar_lander]") {
  LunarLander env;
  Vec obs(8);
  env.reset(3, obs);
  bool seen[2] = {false, false};
  for (int t = 0; t < 1000; ++t) {
    const auto a = lunar_lander_heuristic(obs, false);
    const auto r = act(env, static_cast<int>(a[0]), obs);
    for (int leg = 0; leg < 2; ++leg) {
      CHECK(obs[6 + leg] == (env.leg_contact(leg) ? 1.0f : 0.0f));
      seen[leg] = seen[leg] || env.leg_contact(leg);
    }
    if (r.terminated) {
      CHECK(r.reward == 100);  // the heuristic lands and comes to rest on its legs
      CHECK((obs[6] == 1.0f || obs[7] == 1.0f));
      break;
    }
    // Legs alone touching the ground never end the episode.
    CHECK(!env.game_over());
  }
  CHECK(seen[0]);
  CHECK(seen[1]);
}

TEST_CASE("lunar lander: wind changes the trajectory only when enabled", "[lunar_lander]") {
  LunarLander::Config calm, strong_but_off, windy;
  strong_but_off.wind_power = 20;
  strong_but_off.turbulence_power = 2;
  windy.enable_wind = true;
  LunarLander a(calm), b(strong_but_off), c(windy);
  Vec oa(8), ob(8), oc(8);
  a.reset(7, oa);
  b.reset(7, ob);
  c.reset(7, oc);
  CHECK(oa == ob);
  CHECK(a.terrain_y() == c.terrain_y());  // the wind offsets are drawn after the terrain
  CHECK(c.wind_index() >= -9999);
  CHECK(c.wind_index() <= 9998);
  const int wind0 = c.wind_index(), torque0 = c.torque_index();
  for (int t = 0; t < 40; ++t) {
    act(a, LunarLander::kNoop, oa);
    act(b, LunarLander::kNoop, ob);
    act(c, LunarLander::kNoop, oc);
  }
  CHECK(oa == ob);
  CHECK(oa != oc);
  CHECK(oc[5] != oa[5]);  // turbulence torque
  // One index step per windy step while no leg touches (the reset's step was
  // the first).
  CHECK(c.wind_index() == wind0 + 40);
  CHECK(c.torque_index() == torque0 + 40);
  // v3: each reset draws new offsets.
  c.reset(8, oc);
  CHECK(c.wind_index() != wind0);
}

TEST_CASE("lunar lander: continuous throttles and their dead zones", "[lunar_lander]") {
  LunarLander env(continuous_config());
  Vec obs(8), prev(8);
  struct Case {
    float main, lateral;
    double m_power, s_power;
  };
  const Case cases[] = {
      {-1.0f, 0.0f, 0.0, 0.0},  {0.0f, 0.0f, 0.0, 0.0},   {0.01f, 0.0f, 0.505, 0.0},
      {0.5f, 0.0f, 0.75, 0.0},  {1.0f, 0.0f, 1.0, 0.0},   {3.0f, 0.0f, 1.0, 0.0},
      {-1.0f, 0.5f, 0.0, 0.0},  {-1.0f, -0.5f, 0.0, 0.0}, {-1.0f, 0.51f, 0.0, 0.51},
      {-1.0f, -0.7f, 0.0, 0.7}, {-1.0f, 1.0f, 0.0, 1.0},  {-1.0f, -5.0f, 0.0, 1.0},
      {0.2f, 0.9f, 0.6, 0.9},
  };
  env.reset(2, obs);
  for (const Case& c : cases) {
    prev = obs;
    const auto r = act(env, c.main, c.lateral, obs);
    INFO("action " << c.main << ", " << c.lateral);
    REQUIRE(!r.terminated);
    CHECK(env.main_power() == Approx(c.m_power).margin(1e-6));
    CHECK(env.side_power() == Approx(c.s_power).margin(1e-6));
    CHECK(r.reward ==
          Approx(shaping(obs) - shaping(prev) - 0.3 * c.m_power - 0.03 * c.s_power).margin(2e-3));
  }
  // Full throttles are the discrete actions: same seed, same impulses, same
  // trajectory.
  LunarLander discrete;
  Vec od(8);
  const std::pair<int, std::array<float, 2>> same[] = {{LunarLander::kMainEngine, {1.0f, 0.0f}},
                                                       {LunarLander::kLeftEngine, {-1.0f, -1.0f}},
                                                       {LunarLander::kRightEngine, {-1.0f, 1.0f}},
                                                       {LunarLander::kNoop, {-0.3f, 0.2f}}};
  for (const auto& [action, throttles] : same) {
    discrete.reset(9, od);
    env.reset(9, obs);
    for (int t = 0; t < 30; ++t) {
      act(discrete, action, od);
      act(env, throttles[0], throttles[1], obs);
    }
    CHECK(od == obs);
  }
}

TEST_CASE(
    "lunar lander: Gymnasium's heuristic lands (mean return > 200 over "
    "20 seeds)",
    "[lunar_lander]") {
  for (const bool continuous : {false, true}) {
    LunarLander::Config config;
    config.continuous = continuous;
    LunarLander env(config);
    std::vector<double> returns;
    for (uint64_t seed = 0; seed < 20; ++seed) returns.push_back(heuristic_return(env, seed));
    const double mean = std::accumulate(returns.begin(), returns.end(), 0.0) / returns.size();
    INFO((continuous ? "continuous" : "discrete") << " mean " << mean);
    CHECK(mean > 200);
    int landed = 0;
    for (double r : returns) landed += r > 100;
    CHECK(landed >= 17);
  }
}

TEST_CASE("lunar lander: env checker, also through the registry", "[lunar_lander][env_checker]") {
  for (const bool continuous : {false, true}) {
    LunarLander::Config config;
    config.continuous = continuous;
    TimeLimit env(std::make_unique<LunarLander>(config), LunarLander::kMaxEpisodeSteps);
    for (uint64_t seed : {0, 5}) {
      const auto problems = check_env(env, seed, 400);
      std::string all;
      for (const auto& p : problems) all += p + "\n";
      INFO(all);
      CHECK(problems.empty());
    }
  }
}

TEST_CASE("lunar lander: the picture", "[lunar_lander][render]") {
  LunarLander env;
  Vec obs(8);
  env.reset(1, obs);
  REQUIRE(env.render_spec().width == 600);
  REQUIRE(env.render_spec().height == 400);
  CHECK(env.render_spec().fps == 50);
  Frame frame(600, 400);
  REQUIRE(env.render(frame));
  // Black sky at the top, white ground at the bottom (the terrain is at most
  // 0.99 * H/2).
  CHECK(frame.pixel(5, 5) == Rgb{0, 0, 0});
  CHECK(frame.pixel(300, 395) == Rgb{255, 255, 255});
  // The lander's hull at the top centre: it starts with its centre on the top
  // edge and reaches 10 px below it (LANDER_POLY's bottom is at -10 px).
  CHECK(frame.pixel(300, 3) == Rgb{128, 102, 230});
  // The flags: yellow near each pole's top (flag y2 = helipad_y*30 + 50 = 150
  // px up).
  const int flag_row = 400 - static_cast<int>(env.helipad_y() * 30 + 45);
  CHECK(frame.pixel(static_cast<int>(env.helipad_x1() * 30) + 8, flag_row) == Rgb{204, 204, 0});
  CHECK(frame.pixel(static_cast<int>(env.helipad_x2() * 30) + 8, flag_row) == Rgb{204, 204, 0});
}

TEST_CASE("lunar lander: eval and record --policy heuristic", "[lunar_lander][cli]") {
  TempDir dir("lunar_lander_cli");
  const auto r = run_rlrun("eval --env LunarLander-v3 --policy heuristic --episodes 5");
  INFO(r.output);
  REQUIRE(r.exit_code == 0);
  CHECK(r.output.find("heuristic on LunarLander-v3, 5 episodes") != std::string::npos);
  const auto video = run_rlrun(
      "record --env LunarLanderContinuous-v3 --policy heuristic --output " + dir / "lander.mp4");
  INFO(video.output);
  REQUIRE(video.exit_code == 0);
  // One frame for the reset and one per step of the episode.
  std::smatch m;
  REQUIRE(std::regex_search(
      video.output, m, std::regex(R"(recorded 1 episode .*: (\d+) frames at 600x400, 50 fps)")));
  const int frames = std::stoi(m[1].str());
  CHECK(frames > 100);
  CHECK(probe_video(dir / "lander.mp4").find("h264,600,400," + std::to_string(frames)) !=
        std::string::npos);
  const auto wrong = run_rlrun("eval --env CartPole-v1 --policy heuristic --episodes 1");
  CHECK(wrong.exit_code == 2);
}

// Env steps per second on one core, random actions, resets included. Measured,
// not asserted (docs/benchmarks.md): `build/tests/rlrun_tests
// "[lunar_lander_bench]"`, run by scripts/bench.sh.
TEST_CASE("bench: LunarLander-v3 env steps/s", "[.bench][lunar_lander_bench]") {
  std::printf("| run | steps/s |\n|---|---|\n");
  for (const bool continuous : {false, true}) {
    LunarLander::Config config;
    config.continuous = continuous;
    LunarLander env(config);
    Vec obs(8);
    Rng actions(1);
    constexpr int kSteps = 200000;
    int episodes = 1, since_reset = 0;
    const auto start = std::chrono::steady_clock::now();
    env.reset(1, obs);
    for (int i = 0; i < kSteps; ++i) {
      float a[2];
      env.action_space().sample(actions, a);
      const auto r = env.step({a, continuous ? 2u : 1u}, obs);
      if (r.terminated || ++since_reset == LunarLander::kMaxEpisodeSteps) {
        env.reset(std::nullopt, obs);
        ++episodes;
        since_reset = 0;
      }
    }
    const double s =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    std::printf("| %s, random actions, one core (%d episodes) | %.0f |\n", env.id().c_str(),
                episodes, kSteps / s);
  }
}
