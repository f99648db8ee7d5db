// The probe envs (envs/probe/): SB3's identity and multi-input test envs and DictReach-v0.
// Learning through the real binary is in tests/runtime/test_cli_spaces.cpp.
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <string>
#include <vector>

#include "rlrun/envs/probe/dict_reach.hpp"
#include "rlrun/envs/probe/identity_env.hpp"
#include "rlrun/envs/probe/simple_multi_obs.hpp"
#include "rlrun/frame.hpp"

using namespace rlrun;

namespace {

std::vector<uint8_t> pixels(const Frame& frame) {
  std::vector<uint8_t> rgb;
  frame.to_rgb(rgb);
  return rgb;
}

// render() after reset shows what render_observation() shows for the reset observation.
void check_render_matches_observation(Env& env, std::span<const float> obs) {
  const RenderSpec spec = env.render_spec();
  REQUIRE(spec.width > 0);
  Frame a(spec.width, spec.height), b(spec.width, spec.height);
  CHECK(env.render(a));
  CHECK(env.render_observation(obs, b));
  CHECK(pixels(a) == pixels(b));
  std::vector<float> outside(obs.begin(), obs.end());
  outside[0] = 99.0f;
  CHECK_THROWS_AS(env.render_observation(outside, b), std::invalid_argument);
}

}  // namespace

TEST_CASE("identity envs reward the action that equals the observation", "[envs][probe]") {
  IdentityMultiDiscrete env(IdentityMultiDiscrete::Config{});
  CHECK(env.observation_space() == Space::multi_discrete({4, 4}));
  CHECK(env.action_space() == env.observation_space());
  std::vector<float> obs(2), next(2);
  env.reset(3, obs);
  check_render_matches_observation(env, obs);
  CHECK(env.step(obs, next).reward == 1.0);
  std::vector<float> wrong = next;
  wrong[1] = wrong[1] == 0.0f ? 1.0f : 0.0f;
  const StepResult miss = env.step(wrong, obs);
  CHECK(miss.reward == 0.0);
  CHECK_FALSE(miss.terminated);  // only the registered TimeLimit ends episodes
  CHECK_THROWS_AS(env.step(std::vector<float>{4.0f, 0.0f}, obs), std::invalid_argument);

  IdentityBox::Config box_config;
  box_config.eps = 0.1;
  IdentityBox box(box_config);
  std::vector<float> x(1), y(1);
  box.reset(1, x);
  CHECK(box.step(std::vector<float>{x[0] + 0.09f}, y).reward == 1.0);
  CHECK(box.step(std::vector<float>{y[0] + 0.11f}, x).reward == 0.0);
  CHECK_THROWS_AS(IdentityBox(IdentityBox::Config{1.0, 1.0, 0.1}), std::invalid_argument);

  IdentityMultiBinary bits(IdentityMultiBinary::Config{});
  std::vector<float> b(4), c(4);
  bits.reset(7, b);
  CHECK(bits.step(b, c).reward == 1.0);
  IdentityDiscrete discrete(IdentityDiscrete::Config{});
  std::vector<float> d(1), e(1);
  discrete.reset(7, d);
  CHECK(discrete.observation_space() == Space::discrete(4));
  CHECK(discrete.step(d, e).reward == 1.0);
}

TEST_CASE("SimpleMultiObsEnv: the ring grid, its Dict observation and SB3's rewards",
          "[envs][probe]") {
  SimpleMultiObs::Config config;
  config.random_start = false;
  SimpleMultiObs env(config);
  const Space& space = env.observation_space();
  REQUIRE(space.keys() == std::vector<std::string>{"moves", "row", "vec"});
  std::vector<float> obs(static_cast<size_t>(space.flat_dim()));
  env.reset(0, obs);
  CHECK(env.state() == 0);
  check_render_matches_observation(env, obs);
  // Cell 0: down and right lead somewhere; row 0.
  CHECK(std::vector<float>(obs.begin(), obs.begin() + 5) == std::vector<float>{0, 1, 1, 0, 0});
  const std::vector<float> column0(obs.begin() + 5, obs.end());
  // Up from 0 is blocked; then right, right, right, down, down, down reaches 15.
  std::vector<float> action{3};
  CHECK(env.step(action, obs).reward == Approx(-0.1));
  CHECK(env.state() == 0);
  double ret = 0;
  StepResult r;
  for (float a : {2.0f, 2.0f, 2.0f, 1.0f, 1.0f, 1.0f}) {
    action[0] = a;
    r = env.step(action, obs);
    ret += r.reward;
  }
  CHECK(env.state() == SimpleMultiObs::kGoal);
  CHECK(r.terminated);
  CHECK(ret == Approx(0.5));
  CHECK(obs[4] == 3.0f);  // row 3
  CHECK(std::vector<float>(obs.begin() + 5, obs.end()) != column0);
  // The walls are never entered.
  for (int cell = 0; cell < 16; ++cell)
    for (int a = 0; a < 4; ++a)
      if (!SimpleMultiObs::is_wall(cell))
        CHECK_FALSE(SimpleMultiObs::is_wall(SimpleMultiObs::next_cell(cell, a)));

  // Random starts are free, non-goal cells; every copy shows the same column vectors.
  SimpleMultiObs other;
  std::vector<float> o(obs.size());
  for (uint64_t seed = 0; seed < 50; ++seed) {
    other.reset(seed, o);
    CHECK_FALSE(SimpleMultiObs::is_wall(other.state()));
    CHECK(other.state() != SimpleMultiObs::kGoal);
    if (other.state() % 4 == 0) CHECK(std::vector<float>(o.begin() + 5, o.end()) == column0);
  }
}

TEST_CASE("DictReach: goal then position in the flat observation, reward -distance",
          "[envs][probe]") {
  DictReach env;
  std::vector<float> obs(4);
  env.reset(5, obs);
  check_render_matches_observation(env, obs);
  const double start = env.distance();
  // Move towards the goal: obs[0..2) is the goal, obs[2..4) the position.
  std::vector<float> action{obs[0] > obs[2] ? 1.0f : -1.0f, obs[1] > obs[3] ? 1.0f : -1.0f};
  const StepResult r = env.step(action, obs);
  CHECK(env.distance() < start);
  CHECK(r.reward == Approx(-env.distance()));
  // Walk straight at the goal until the episode ends with success.
  bool done = false;
  for (int t = 0; t < 100 && !done; ++t) {
    const float dx = obs[0] - obs[2], dy = obs[1] - obs[3];
    const float len = std::max(std::hypot(dx, dy), 1e-6f);
    const float scale = std::min(1.0f, len / 0.1f) / len;
    action = {dx * scale, dy * scale};
    done = env.step(action, obs).terminated;
  }
  CHECK(done);
  CHECK(env.info().get(env.info().find("is_success")) == 1.0);
  CHECK_THROWS_AS(env.step(std::vector<float>{NAN, 0.0f}, obs), std::invalid_argument);
}
