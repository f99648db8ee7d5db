// Swimmer-v4 (gymnasium/envs/mujoco/swimmer_v4.py): spaces and kwargs, transitions and every
// info key against the tests' own MuJoCo stepping and Gymnasium's formulas, and the reset noise.
#include <catch2/catch.hpp>
#include <vector>

#include "envs/mujoco/mujoco_reference.hpp"
#include "envs/mujoco/mujoco_task_test.hpp"
#include "rlrun/envs/mujoco/swimmer.hpp"
#include "rlrun/runtime/components/builtins.hpp"
#include "rlrun/runtime/components/registry.hpp"

using namespace rlrun;
using namespace rlrun::testing;
using rlrun::mujoco::Swimmer;

TEST_CASE("Swimmer-v4: Gymnasium's spaces, kwargs and time limit", "[mujoco]") {
  Swimmer env;
  CHECK(env.id() == "Swimmer-v4");
  CHECK(env.observation_space().shape() == std::vector<int>{8});
  CHECK(env.action_space().shape() == std::vector<int>{2});
  CHECK(env.action_space().low() == std::vector<float>(2, -1.0f));
  CHECK(env.action_space().high() == std::vector<float>(2, 1.0f));
  CHECK(env.frame_skip() == 4);
  CHECK(env.dt() == 0.01 * 4);
  Swimmer::Config with_xy;
  with_xy.exclude_current_positions_from_observation = false;
  CHECK(Swimmer(with_xy).observation_space().shape() == std::vector<int>{10});
  const Swimmer::Config defaults;
  CHECK(defaults.forward_reward_weight == 1.0);
  CHECK(defaults.ctrl_cost_weight == 1e-4);
  CHECK(defaults.reset_noise_scale == 0.1);
  CHECK(defaults.exclude_current_positions_from_observation);
  const EnvEntry* entry = builtin_registry().find_env("Swimmer-v4");
  REQUIRE(entry);
  CHECK(entry->max_episode_steps == 1000);
  CHECK(entry->independent_copies);
}

TEST_CASE("Swimmer-v4: a step equals MuJoCo's C API stepped as Gymnasium does", "[mujoco]") {
  Swimmer::Config config;
  config.forward_reward_weight = 1.5;
  config.ctrl_cost_weight = 0.01;
  Swimmer env(config);
  Swimmer::Config with_xy;
  with_xy.exclude_current_positions_from_observation = false;
  Swimmer env_xy(with_xy);
  ReferenceSim sim("swimmer.xml");
  std::vector<float> obs(8), obs_xy(10);
  env.reset(3, obs);
  // The same history as the env: MuJoCo's solver starts from the last state's accelerations
  // (qacc_warmstart), which set_state keeps, in Gymnasium as here.
  sim.set_state(env.qpos(), env.qvel());
  env_xy.reset(3, obs_xy);
  Rng rng(13);
  for (int trial = 0; trial < 30; ++trial) {
    const std::vector<double> qpos = random_values(rng, 5, -1.5, 1.5);
    const std::vector<double> qvel = random_values(rng, 5, -2.0, 2.0);
    env.set_state(qpos, qvel);
    env_xy.set_state(qpos, qvel);
    sim.set_state(qpos, qvel);
    const std::vector<float> action = random_controls(rng, 2, 1.5);

    const double x_before = sim.data().qpos[0], y_before = sim.data().qpos[1];
    sim.step(action, 4);
    const StepResult r = env.step(action, obs);
    env_xy.step(action, obs_xy);

    const mjData& d = sim.data();
    const double dt = sim.model().opt.timestep * 4;
    const double x_velocity = (d.qpos[0] - x_before) / dt;
    const double y_velocity = (d.qpos[1] - y_before) / dt;
    const double forward_reward = 1.5 * x_velocity;
    const double ctrl_cost = 0.01 * static_cast<double>(numpy_float32_sum_of_squares(action));
    CHECK(r.reward == forward_reward - ctrl_cost);
    CHECK_FALSE(r.terminated);
    CHECK_FALSE(r.truncated);
    for (int i = 0; i < 3; ++i) CHECK(obs[i] == static_cast<float>(d.qpos[i + 2]));
    for (int i = 0; i < 5; ++i) CHECK(obs[3 + i] == static_cast<float>(d.qvel[i]));
    for (int i = 0; i < 5; ++i) CHECK(obs_xy[i] == static_cast<float>(d.qpos[i]));
    CHECK(info_value(env, "reward_fwd") == forward_reward);
    CHECK(info_value(env, "reward_ctrl") == -ctrl_cost);
    CHECK(info_value(env, "x_position") == d.qpos[0]);
    CHECK(info_value(env, "y_position") == d.qpos[1]);
    CHECK(info_value(env, "distance_from_origin") == numpy_norm(std::vector{d.qpos[0], d.qpos[1]}));
    CHECK(info_value(env, "x_velocity") == x_velocity);
    CHECK(info_value(env, "y_velocity") == y_velocity);
    CHECK(info_value(env, "forward_reward") == forward_reward);
  }
}

TEST_CASE("Swimmer-v4: reset draws U(-scale, scale) for qpos, then for qvel", "[mujoco]") {
  Swimmer env;
  std::vector<float> obs(8);
  for (uint64_t seed = 0; seed < 20; ++seed) {
    env.reset(seed, obs);
    Rng expected(seed);
    for (int i = 0; i < 5; ++i) {
      const double noise = expected.uniform(-0.1, 0.1);
      CHECK(env.qpos()[i] == env.init_qpos()[i] + noise);
    }
    for (int i = 0; i < 5; ++i) {
      const double noise = expected.uniform(-0.1, 0.1);
      CHECK(env.qvel()[i] == env.init_qvel()[i] + noise);
    }
    for (int i = 0; i < 3; ++i) CHECK(obs[i] == static_cast<float>(env.qpos()[i + 2]));
  }
}
