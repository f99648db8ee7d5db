// Walker2d-v4 (gymnasium/envs/mujoco/walker2d_v4.py): spaces and kwargs, transitions against
// the tests' own MuJoCo stepping and Gymnasium's formulas, the healthy rules at their
// boundaries, and the reset noise.
#include <catch2/catch.hpp>
#include <cmath>
#include <limits>
#include <vector>

#include "envs/mujoco/mujoco_reference.hpp"
#include "envs/mujoco/mujoco_task_test.hpp"
#include "rlrun/envs/mujoco/walker2d.hpp"
#include "rlrun/runtime/components/builtins.hpp"
#include "rlrun/runtime/components/registry.hpp"

using namespace rlrun;
using namespace rlrun::testing;
using rlrun::mujoco::RangeKwarg;
using rlrun::mujoco::Walker2d;

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// Gymnasium's is_healthy with the default ranges: 0.8 < z < 2 and -1 < angle < 1.
bool walker_healthy(const mjData& d) {
  const double z = d.qpos[1], angle = d.qpos[2];
  return 0.8 < z && z < 2.0 && -1.0 < angle && angle < 1.0;
}

}  // namespace

TEST_CASE("Walker2d-v4: Gymnasium's spaces, kwargs and time limit", "[mujoco]") {
  Walker2d env;
  CHECK(env.id() == "Walker2d-v4");
  CHECK(env.observation_space().shape() == std::vector<int>{17});
  CHECK(env.action_space().shape() == std::vector<int>{6});
  CHECK(env.action_space().low() == std::vector<float>(6, -1.0f));
  CHECK(env.action_space().high() == std::vector<float>(6, 1.0f));
  CHECK(env.frame_skip() == 4);
  CHECK(env.dt() == 0.002 * 4);
  Walker2d::Config with_x;
  with_x.exclude_current_positions_from_observation = false;
  CHECK(Walker2d(with_x).observation_space().shape() == std::vector<int>{18});

  const Walker2d::Config defaults;
  CHECK(defaults.forward_reward_weight == 1.0);
  CHECK(defaults.ctrl_cost_weight == 1e-3);
  CHECK(defaults.healthy_reward == 1.0);
  CHECK(defaults.terminate_when_unhealthy);
  CHECK(defaults.healthy_z_range == RangeKwarg{0.8, 2.0});
  CHECK(defaults.healthy_angle_range == RangeKwarg{-1.0, 1.0});
  CHECK(defaults.reset_noise_scale == 5e-3);
  CHECK(defaults.exclude_current_positions_from_observation);

  const EnvEntry* entry = builtin_registry().find_env("Walker2d-v4");
  REQUIRE(entry);
  CHECK(entry->max_episode_steps == 1000);
  CHECK(entry->independent_copies);
  const Walker2d::Config parsed =
      entry->parse(ConfigNode::load_string("healthy_z_range: [0.5, .inf]", "exp.yaml"))
          .get<Walker2d::Config>();
  CHECK(parsed.healthy_z_range == RangeKwarg{0.5, kInf});
}

TEST_CASE("Walker2d-v4: a step equals MuJoCo's C API stepped as Gymnasium does", "[mujoco]") {
  Walker2d env;
  ReferenceSim sim("walker2d.xml");
  std::vector<float> obs(17);
  env.reset(3, obs);
  // The same history as the env: MuJoCo's solver starts from the last state's accelerations
  // (qacc_warmstart), which set_state keeps, in Gymnasium as here.
  sim.set_state(env.qpos(), env.qvel());
  Rng rng(12);
  int unhealthy = 0, clipped = 0;
  for (int trial = 0; trial < 40; ++trial) {
    std::vector<double> qpos = random_values(rng, 9, -0.5, 0.5);
    qpos[1] = rng.uniform(0.6, 2.2);
    qpos[2] = rng.uniform(-1.4, 1.4);
    const std::vector<double> qvel = random_values(rng, 9, -12.0, 12.0);
    env.set_state(qpos, qvel);
    sim.set_state(qpos, qvel);
    const std::vector<float> action = random_controls(rng, 6, 1.5);

    const double x_before = sim.data().qpos[0];
    sim.step(action, 4);
    const StepResult r = env.step(action, obs);

    const mjData& d = sim.data();
    const double x_velocity = (d.qpos[0] - x_before) / (sim.model().opt.timestep * 4);
    const double ctrl_cost = 1e-3 * static_cast<double>(numpy_float32_sum_of_squares(action));
    const bool healthy = walker_healthy(d);
    CHECK(r.reward == (x_velocity + 1.0) - ctrl_cost);
    CHECK(r.terminated == !healthy);
    CHECK_FALSE(r.truncated);
    for (int i = 0; i < 8; ++i) CHECK(obs[i] == static_cast<float>(d.qpos[i + 1]));
    for (int i = 0; i < 9; ++i) {
      CHECK(obs[8 + i] == static_cast<float>(std::clamp(d.qvel[i], -10.0, 10.0)));
      clipped += std::abs(d.qvel[i]) > 10.0;
    }
    CHECK(info_value(env, "x_position") == d.qpos[0]);
    CHECK(info_value(env, "x_velocity") == x_velocity);
    unhealthy += !healthy;
  }
  CHECK(unhealthy > 0);
  CHECK(unhealthy < 40);
  CHECK(clipped > 0);
}

TEST_CASE("Walker2d-v4: the healthy ranges are open at both ends, and unhealthy ends the episode",
          "[mujoco]") {
  std::vector<double> qpos(9, 0.0), qvel(9, 0.0);
  qpos[1] = 1.25;
  qpos[2] = 0.2;
  qvel[0] = 0.4;
  const std::vector<float> action{0.3f, -0.6f, 0.9f, -0.2f, 0.5f, 0.1f};
  // Each env below is reset with seed 0, then set to this state: the reference goes through the
  // same states (the solver's warm start carries over set_state).
  Walker2d after_reset;
  std::vector<float> reset_obs(17);
  after_reset.reset(0, reset_obs);
  ReferenceSim sim("walker2d.xml");
  sim.set_state(after_reset.qpos(), after_reset.qvel());
  sim.set_state(qpos, qvel);
  sim.step(action, 4);
  const double z = sim.data().qpos[1], angle = sim.data().qpos[2];
  REQUIRE(walker_healthy(sim.data()));

  const auto step_with = [&](const Walker2d::Config& config) {
    Walker2d env(config);
    std::vector<float> obs(17);
    env.reset(0, obs);
    env.set_state(qpos, qvel);
    return env.step(action, obs);
  };
  const auto terminated_with = [&](auto&& change) {
    Walker2d::Config config;
    change(config);
    return step_with(config).terminated;
  };
  const auto down = [](double v) { return std::nextafter(v, -kInf); };
  const auto up = [](double v) { return std::nextafter(v, kInf); };
  CHECK_FALSE(terminated_with([](Walker2d::Config&) {}));
  CHECK(terminated_with([&](Walker2d::Config& c) { c.healthy_z_range = {z, 2.0}; }));
  CHECK_FALSE(terminated_with([&](Walker2d::Config& c) { c.healthy_z_range = {down(z), 2.0}; }));
  CHECK(terminated_with([&](Walker2d::Config& c) { c.healthy_z_range = {0.0, z}; }));
  CHECK_FALSE(terminated_with([&](Walker2d::Config& c) { c.healthy_z_range = {0.0, up(z)}; }));
  CHECK(terminated_with([&](Walker2d::Config& c) { c.healthy_angle_range = {angle, 1.0}; }));
  CHECK_FALSE(terminated_with([&](Walker2d::Config& c) {
    c.healthy_angle_range = {down(angle), 1.0};
  }));
  CHECK(terminated_with([&](Walker2d::Config& c) { c.healthy_angle_range = {-1.0, angle}; }));
  CHECK_FALSE(terminated_with([&](Walker2d::Config& c) {
    c.healthy_angle_range = {-1.0, up(angle)};
  }));

  const double x_velocity = (sim.data().qpos[0] - qpos[0]) / (sim.model().opt.timestep * 4);
  const double ctrl_cost = 1e-3 * static_cast<double>(numpy_float32_sum_of_squares(action));
  Walker2d::Config lenient;
  lenient.terminate_when_unhealthy = false;
  lenient.healthy_z_range = {z, 2.0};  // unhealthy
  StepResult r = step_with(lenient);
  CHECK_FALSE(r.terminated);
  CHECK(r.reward == (x_velocity + 0.0) - ctrl_cost);
  lenient.healthy_z_range = {0.8, 2.0};  // healthy
  CHECK(step_with(lenient).reward == (x_velocity + 1.0) - ctrl_cost);
  Walker2d::Config strict;
  strict.healthy_angle_range = {angle, 1.0};
  r = step_with(strict);
  CHECK(r.terminated);
  CHECK(r.reward == (x_velocity + 1.0) - ctrl_cost);

  // A fallen walker (torso near the floor) is terminated.
  Walker2d env;
  std::vector<float> obs(17);
  env.reset(0, obs);
  std::vector<double> fallen(env.init_qpos().begin(), env.init_qpos().end());
  fallen[1] = 0.3;
  env.set_state(fallen, std::vector<double>(9, 0.0));
  CHECK(env.step(std::vector<float>(6, 0.0f), obs).terminated);
}

TEST_CASE("Walker2d-v4: reset draws U(-scale, scale) for qpos, then for qvel", "[mujoco]") {
  Walker2d env;
  std::vector<float> obs(17);
  for (uint64_t seed = 0; seed < 20; ++seed) {
    env.reset(seed, obs);
    Rng expected(seed);
    for (int i = 0; i < 9; ++i) {
      const double noise = expected.uniform(-5e-3, 5e-3);
      CHECK(env.qpos()[i] == env.init_qpos()[i] + noise);
    }
    for (int i = 0; i < 9; ++i) {
      const double noise = expected.uniform(-5e-3, 5e-3);
      CHECK(env.qvel()[i] == env.init_qvel()[i] + noise);
    }
    for (int i = 0; i < 8; ++i) CHECK(obs[i] == static_cast<float>(env.qpos()[i + 1]));
  }
}
