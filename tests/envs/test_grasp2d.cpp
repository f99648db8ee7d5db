// Grasp2D-v0's rules: spaces, reset ranges and options, moves, the grasp and the workspace
// failure with their rewards and info, shaping, seeding, resume state, the env checker and
// drawing.
#include <catch2/catch.hpp>
#include <cmath>
#include <vector>

#include "rlrun/core/config_fields.hpp"
#include "rlrun/env/env_checker.hpp"
#include "rlrun/envs/grasp2d/grasp2d.hpp"
#include "rlrun/frame.hpp"
#include "rlrun/runtime/components/builtins.hpp"

using namespace rlrun;

namespace {

using Vec = std::vector<float>;

StepResult act(Grasp2D& env, int action, Vec& obs) {
  const float a = static_cast<float>(action);
  return env.step({&a, 1}, obs);
}

double info_of(const Env& env, const char* key) { return env.info().get(env.info().find(key)); }

// An env whose arm and object are placed by reset options.
Grasp2D placed(double ax, double ay, double ox, double oy, Vec& obs, Grasp2D::Config config = {}) {
  Grasp2D env(config);
  Grasp2D::ResetOptions options;
  options.arm = {ax, ay};
  options.object = {ox, oy};
  env.reset(7, options, obs);
  return env;
}

}  // namespace

TEST_CASE("grasp2d: spaces, registration and time limit", "[grasp2d]") {
  Grasp2D env;
  CHECK(env.id() == "Grasp2D-v0");
  CHECK(env.observation_space().describe() == "Box(0.0, 1.0, (6,), float32)");
  CHECK(env.action_space().describe() == "Discrete(6)");
  const EnvEntry* entry = builtin_registry().find_env("Grasp2D-v0");
  REQUIRE(entry != nullptr);
  CHECK(entry->max_episode_steps == 100);
  std::vector<std::string> keys;
  for (const auto& row : entry->params()) keys.push_back(row.key);
  for (const char* k : {"step_size", "success_threshold", "success_reward", "failure_penalty",
                        "step_penalty", "distance_scale"})
    CHECK(std::find(keys.begin(), keys.end(), k) != keys.end());
  CHECK(std::string(Grasp2D::action_name(Grasp2D::kClose)) == "close");
  CHECK(std::string(Grasp2D::action_name(Grasp2D::kLeft)) == "left");
}

TEST_CASE("grasp2d: reset draws positions inside the spawn square, open gripper", "[grasp2d]") {
  Grasp2D env;
  Vec obs(6);
  for (uint64_t seed = 0; seed < 50; ++seed) {
    env.reset(seed, obs);
    for (int i = 0; i < 4; ++i) {
      CHECK(obs[i] >= 0.1f);
      CHECK(obs[i] <= 0.9f);
    }
    CHECK(obs[4] == 0.0f);
    CHECK(obs[5] == 0.0f);
    CHECK(info_of(env, "is_success") == 0.0);
    CHECK(info_of(env, "is_failure") == 0.0);
  }
  // Fixed positions from the config.
  Grasp2D::Config config;
  config.arm_start = {0.2, 0.3};
  config.object_start = {0.6, 0.7};
  Grasp2D fixed(config);
  fixed.reset(3, obs);
  CHECK(obs == Vec{0.2f, 0.3f, 0.6f, 0.7f, 0.0f, 0.0f});
  config.arm_start = {1.5, 0.3};
  CHECK_THROWS_AS(Grasp2D(config), std::invalid_argument);
}

TEST_CASE("grasp2d: moves change the arm by step_size, shaping reward", "[grasp2d]") {
  Vec obs(6);
  Grasp2D env = placed(0.5, 0.5, 0.8, 0.5, obs);
  StepResult r = act(env, Grasp2D::kRight, obs);
  CHECK(obs[0] == Approx(0.55f));
  CHECK(obs[1] == Approx(0.5f));
  CHECK_FALSE(r.terminated);
  CHECK_FALSE(r.truncated);
  CHECK(r.reward == Approx(-0.01 - 0.1 * 0.25));
  CHECK(info_of(env, "distance") == Approx(0.25));
  CHECK(info_of(env, "action") == 1.0);  // right
  act(env, Grasp2D::kUp, obs);
  CHECK(obs[1] == Approx(0.55f));
  act(env, Grasp2D::kDown, obs);
  act(env, Grasp2D::kLeft, obs);
  CHECK(obs[0] == Approx(0.5f));
  CHECK(obs[1] == Approx(0.5f));
  // Open/close toggle the gripper flag and keep the arm in place.
  r = act(env, Grasp2D::kClose, obs);
  CHECK(obs[4] == 1.0f);
  CHECK_FALSE(r.terminated);  // too far to grasp
  CHECK(obs[5] == 0.0f);
  act(env, Grasp2D::kOpen, obs);
  CHECK(obs[4] == 0.0f);
  CHECK(obs[0] == Approx(0.5f));
}

TEST_CASE("grasp2d: closing within the threshold grasps (success)", "[grasp2d]") {
  Vec obs(6);
  Grasp2D env = placed(0.5, 0.5, 0.53, 0.52, obs);
  const StepResult r = act(env, Grasp2D::kClose, obs);
  CHECK(r.terminated);
  CHECK_FALSE(r.truncated);
  CHECK(r.reward == 10.0);
  CHECK(obs[4] == 1.0f);
  CHECK(obs[5] == 1.0f);
  CHECK(info_of(env, "is_success") == 1.0);
  CHECK(info_of(env, "is_failure") == 0.0);
  CHECK(env.grasped());
  // Just outside the threshold: no grasp; the reward constants come from the config.
  Grasp2D::Config config;
  config.success_threshold = 0.02;
  config.success_reward = 3.0;
  Grasp2D strict = placed(0.5, 0.5, 0.53, 0.52, obs, config);
  CHECK_FALSE(act(strict, Grasp2D::kClose, obs).terminated);
  Grasp2D near = placed(0.5, 0.5, 0.51, 0.51, obs, config);
  CHECK(act(near, Grasp2D::kClose, obs).reward == 3.0);
}

TEST_CASE("grasp2d: leaving the workspace fails", "[grasp2d]") {
  Vec obs(6);
  Grasp2D env = placed(0.02, 0.5, 0.5, 0.5, obs);
  const StepResult r = act(env, Grasp2D::kLeft, obs);
  CHECK(r.terminated);
  CHECK(r.reward == -10.0);
  CHECK(info_of(env, "is_failure") == 1.0);
  CHECK(info_of(env, "is_success") == 0.0);
  CHECK(env.observation_space().contains(obs));  // the arm stops at the border
  CHECK(obs[0] == 0.0f);
  // Stepping onto the border exactly is allowed, even after rounding errors: 20 steps of 0.05
  // from 0.0 reach 1.0.
  Grasp2D edge = placed(0.0, 0.0, 0.5, 0.5, obs);
  for (int i = 0; i < 20; ++i) REQUIRE_FALSE(act(edge, Grasp2D::kRight, obs).terminated);
  CHECK(obs[0] == Approx(1.0f));
  CHECK(act(edge, Grasp2D::kRight, obs).terminated);
  Grasp2D top = placed(0.5, 0.97, 0.5, 0.5, obs);
  CHECK(act(top, Grasp2D::kUp, obs).terminated);
}

TEST_CASE("grasp2d: step before reset and invalid actions throw", "[grasp2d]") {
  Grasp2D env;
  Vec obs(6);
  CHECK_THROWS_AS(act(env, 0, obs), std::logic_error);
  env.reset(0, obs);
  CHECK_THROWS_AS(act(env, 6, obs), std::invalid_argument);
  CHECK_THROWS_AS(act(env, -1, obs), std::invalid_argument);
}

TEST_CASE("grasp2d: a greedy walk then close succeeds within the time limit", "[grasp2d]") {
  // The spawn margin guarantees a grid point of the arm within reach of any object.
  Grasp2D env;
  Vec obs(6);
  for (uint64_t seed = 0; seed < 200; ++seed) {
    env.reset(seed, obs);
    int steps = 0;
    bool success = false;
    while (steps < Grasp2D::kMaxEpisodeSteps && !success) {
      const double dx = obs[2] - obs[0], dy = obs[3] - obs[1];
      const double half = env.config().step_size / 2;
      int a = Grasp2D::kClose;
      if (std::abs(dx) > half)
        a = dx > 0 ? Grasp2D::kRight : Grasp2D::kLeft;
      else if (std::abs(dy) > half)
        a = dy > 0 ? Grasp2D::kUp : Grasp2D::kDown;
      const StepResult r = act(env, a, obs);
      ++steps;
      REQUIRE((!r.terminated || info_of(env, "is_success") == 1.0));
      success = r.terminated;
    }
    CHECK(success);
  }
}

TEST_CASE("grasp2d: passes the env checker, resumes from saved state", "[grasp2d]") {
  Grasp2D env;
  CHECK(check_env(env, 3, 400).empty());
  Vec obs(6), a_obs(6), b_obs(6);
  env.reset(11, obs);
  for (int a : {0, 2, 5, 4}) act(env, a, obs);
  TensorMap tensors;
  StateWriter writer(tensors);
  env.write_state(writer);
  Grasp2D restored;
  restored.read_state(StateReader(tensors));
  for (int a : {1, 3, 1, 5}) {
    const StepResult ra = act(env, a, a_obs);
    const StepResult rb = act(restored, a, b_obs);
    CHECK(a_obs == b_obs);
    CHECK(ra.reward == rb.reward);
  }
  env.reset(std::nullopt, a_obs);
  restored.reset(std::nullopt, b_obs);
  CHECK(a_obs == b_obs);  // the RNG stream continues identically
}

TEST_CASE("grasp2d: render draws the arm and the object", "[grasp2d]") {
  Vec obs(6);
  Grasp2D env = placed(0.25, 0.25, 0.75, 0.75, obs);
  Frame frame(env.render_spec().width, env.render_spec().height);
  REQUIRE(env.render(frame));
  // Scene 1.1 units wide, workspace offset 0.05: object centre at pixel (0.8/1.1, 1 - 0.8/1.1).
  const int w = frame.width();
  const auto px = [w](double u) { return static_cast<int>(u / 1.1 * w); };
  const Rgb object = frame.pixel(px(0.8), w - 1 - px(0.8));
  CHECK(object.r > 150);
  CHECK(object.g < 100);
  const Rgb arm = frame.pixel(px(0.3), w - 1 - px(0.3));
  CHECK(arm.b > 150);
  Frame again(100, 100);
  REQUIRE(env.render_observation(obs, again));
}
