// GridWorld-v0's rules: spaces, start cell, moves and walls, the goal, the env's own
// truncation with its penalty, random starts, the OneHotObservation wrapper, resume state,
// the env checker and drawing.
#include <catch2/catch.hpp>
#include <memory>
#include <vector>

#include "rlrun/env/env_checker.hpp"
#include "rlrun/envs/grid_world/grid_world.hpp"
#include "rlrun/frame.hpp"
#include "rlrun/runtime/components/builtins.hpp"
#include "rlrun/wrappers/one_hot_observation.hpp"

using namespace rlrun;

namespace {

using Vec = std::vector<float>;

StepResult act(Env& env, int action, Vec& obs) {
  const float a = static_cast<float>(action);
  return env.step({&a, 1}, obs);
}

double info_of(const Env& env, const char* key) { return env.info().get(env.info().find(key)); }

}  // namespace

TEST_CASE("grid world: spaces, start and registration", "[grid_world]") {
  GridWorld env;
  CHECK(env.id() == "GridWorld-v0");
  CHECK(env.observation_space().describe() == "MultiDiscrete([5 5])");
  CHECK(env.action_space().describe() == "Discrete(4)");
  const EnvEntry* entry = builtin_registry().find_env("GridWorld-v0");
  REQUIRE(entry != nullptr);
  CHECK(entry->max_episode_steps == 0);  // the env truncates itself
  Vec obs(2);
  env.reset(0, obs);
  CHECK(obs == Vec{0, 0});
  CHECK(env.shortest_path_length(0, 0) == 8);
}

TEST_CASE("grid world: moves, walls and the goal", "[grid_world]") {
  GridWorld env;
  Vec obs(2);
  env.reset(0, obs);
  // Up and left from (0, 0) bump the wall: the agent stays, reward -1.
  StepResult r = act(env, GridWorld::kUp, obs);
  CHECK(obs == Vec{0, 0});
  CHECK(r.reward == -1.0);
  CHECK(info_of(env, "bumped") == 1.0);
  r = act(env, GridWorld::kLeft, obs);
  CHECK(obs == Vec{0, 0});
  r = act(env, GridWorld::kRight, obs);
  CHECK(obs == Vec{0, 1});
  CHECK(r.reward == -1.0);
  CHECK(info_of(env, "bumped") == 0.0);
  r = act(env, GridWorld::kDown, obs);
  CHECK(obs == Vec{1, 1});
  // Shortest path to (4, 4): 6 more moves, the last one terminates.
  double total = 0;
  for (int a : {1, 1, 1, 2, 2}) {
    r = act(env, a, obs);
    total += r.reward;
    REQUIRE_FALSE(r.terminated);
  }
  r = act(env, GridWorld::kDown, obs);
  CHECK(obs == Vec{4, 4});
  CHECK(r.terminated);
  CHECK_FALSE(r.truncated);
  CHECK(r.reward == -1.0);
  CHECK(info_of(env, "is_success") == 1.0);
}

TEST_CASE("grid world: truncates after max_steps with the timeout penalty", "[grid_world]") {
  GridWorld env;
  Vec obs(2);
  env.reset(0, obs);
  double total = 0;
  StepResult r;
  for (int t = 0; t < 50; ++t) {
    r = act(env, GridWorld::kUp, obs);  // bump forever
    total += r.reward;
    if (t < 49) REQUIRE_FALSE(r.truncated);
  }
  CHECK(r.truncated);
  CHECK_FALSE(r.terminated);
  CHECK(r.reward == -101.0);
  CHECK(total == -150.0);
  CHECK(info_of(env, "is_success") == 0.0);

  GridWorld::Config config;
  config.max_steps = 3;
  config.timeout_reward = -7;
  config.goal_reward = 5;
  GridWorld short_env(config);
  short_env.reset(0, obs);
  act(short_env, 0, obs);
  act(short_env, 0, obs);
  CHECK(act(short_env, 0, obs).reward == -8.0);
  config.size = 1;
  CHECK_THROWS_AS(GridWorld(config), std::invalid_argument);
}

TEST_CASE("grid world: random starts cover every non-goal cell", "[grid_world]") {
  GridWorld::Config config;
  config.random_start = true;
  GridWorld env(config);
  Vec obs(2);
  std::vector<int> seen(25, 0);
  env.reset(1, obs);
  for (int i = 0; i < 2000; ++i) {
    env.reset(std::nullopt, obs);
    ++seen[static_cast<int>(obs[0]) * 5 + static_cast<int>(obs[1])];
  }
  for (int c = 0; c < 24; ++c) CHECK(seen[c] > 0);
  CHECK(seen[24] == 0);
  CHECK(check_env(env, 5, 300).empty());
}

TEST_CASE("grid world: one-hot observation wrapper", "[grid_world]") {
  auto env = std::make_unique<OneHotObservation>(std::make_unique<GridWorld>());
  CHECK(env->observation_space().describe() == "Box(0.0, 1.0, (10,), float32)");
  Vec obs(10);
  env->reset(0, obs);
  CHECK(obs == Vec{1, 0, 0, 0, 0, 1, 0, 0, 0, 0});
  act(*env, GridWorld::kDown, obs);
  act(*env, GridWorld::kRight, obs);
  act(*env, GridWorld::kRight, obs);
  CHECK(obs == Vec{0, 1, 0, 0, 0, 0, 0, 1, 0, 0});
  CHECK(check_env(*env, 2, 300).empty());
  Frame frame(100, 100);
  CHECK(env->render_observation(obs, frame));
  // A Box env cannot be one-hot encoded.
  struct BoxEnv : GridWorld {
    Space box = Space::box(0.0f, 1.0f, {2});
    const Space& observation_space() const override { return box; }
  };
  CHECK_THROWS_AS(OneHotObservation(std::make_unique<BoxEnv>()), std::invalid_argument);
}

TEST_CASE("grid world: passes the env checker, resumes, renders", "[grid_world]") {
  GridWorld env;
  CHECK(check_env(env, 0, 300).empty());
  Vec obs(2), a_obs(2), b_obs(2);
  env.reset(4, obs);
  for (int a : {1, 2, 2}) act(env, a, obs);
  TensorMap tensors;
  StateWriter writer(tensors);
  env.write_state(writer);
  GridWorld restored;
  restored.read_state(StateReader(tensors));
  CHECK(restored.row() == 2);
  CHECK(restored.col() == 1);
  CHECK(restored.elapsed_steps() == 3);
  Frame frame(env.render_spec().width, env.render_spec().height);
  REQUIRE(env.render(frame));
  // The agent's disc at the centre of cell (2, 1), row 0 at the top; the goal cell is green.
  const Rgb agent = frame.pixel(80 + 40, 160 + 40);
  CHECK(agent.b > 150);
  const Rgb goal = frame.pixel(4 * 80 + 20, 4 * 80 + 20);
  CHECK(goal.g > 150);
  CHECK(goal.r < 150);
}
