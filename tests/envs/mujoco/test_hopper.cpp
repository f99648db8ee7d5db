// Hopper-v4 (gymnasium/envs/mujoco/hopper_v4.py): spaces and kwargs, transitions against the
// tests' own MuJoCo stepping and Gymnasium's formulas, the healthy rules at their boundaries,
// and the reset noise.
#include <catch2/catch.hpp>
#include <cmath>
#include <limits>
#include <vector>

#include "envs/mujoco/mujoco_reference.hpp"
#include "envs/mujoco/mujoco_task_test.hpp"
#include "rlrun/envs/mujoco/hopper.hpp"
#include "rlrun/runtime/components/builtins.hpp"
#include "rlrun/runtime/components/registry.hpp"

using namespace rlrun;
using namespace rlrun::testing;
using rlrun::mujoco::Hopper;
using rlrun::mujoco::RangeKwarg;

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// Gymnasium's is_healthy with the default ranges, by the test's own reading of hopper_v4.py.
bool hopper_healthy(const mjData& d) {
  bool healthy_state = true;
  for (int i = 2; i < 6; ++i)
    healthy_state = healthy_state && -100.0 < d.qpos[i] && d.qpos[i] < 100.0;
  for (int i = 0; i < 6; ++i)
    healthy_state = healthy_state && -100.0 < d.qvel[i] && d.qvel[i] < 100.0;
  const double z = d.qpos[1], angle = d.qpos[2];
  return healthy_state && 0.7 < z && z < kInf && -0.2 < angle && angle < 0.2;
}

// A state near the rest pose, some of them fallen or tilted, velocities beyond the clip of 10.
void random_hopper_state(Rng& rng, std::vector<double>& qpos, std::vector<double>& qvel) {
  qpos = random_values(rng, 6, -0.3, 0.3);
  qpos[1] = rng.uniform(0.6, 1.4);
  qvel = random_values(rng, 6, -12.0, 12.0);
}

}  // namespace

TEST_CASE("Hopper-v4: Gymnasium's spaces, kwargs and time limit", "[mujoco]") {
  Hopper env;
  CHECK(env.id() == "Hopper-v4");
  CHECK(env.observation_space().shape() == std::vector<int>{11});
  CHECK(env.action_space().shape() == std::vector<int>{3});
  CHECK(env.action_space().low() == std::vector<float>(3, -1.0f));
  CHECK(env.action_space().high() == std::vector<float>(3, 1.0f));
  CHECK(env.frame_skip() == 4);
  CHECK(env.dt() == 0.002 * 4);
  CHECK(env.init_qpos()[1] == 1.25);  // rootz's ref: the torso's height at rest
  Hopper::Config with_x;
  with_x.exclude_current_positions_from_observation = false;
  CHECK(Hopper(with_x).observation_space().shape() == std::vector<int>{12});

  const Hopper::Config defaults;
  CHECK(defaults.forward_reward_weight == 1.0);
  CHECK(defaults.ctrl_cost_weight == 1e-3);
  CHECK(defaults.healthy_reward == 1.0);
  CHECK(defaults.terminate_when_unhealthy);
  CHECK(defaults.healthy_state_range == RangeKwarg{-100.0, 100.0});
  CHECK(defaults.healthy_z_range == RangeKwarg{0.7, kInf});
  CHECK(defaults.healthy_angle_range == RangeKwarg{-0.2, 0.2});
  CHECK(defaults.reset_noise_scale == 5e-3);
  CHECK(defaults.exclude_current_positions_from_observation);

  const EnvEntry* entry = builtin_registry().find_env("Hopper-v4");
  REQUIRE(entry);
  CHECK(entry->max_episode_steps == 1000);
  CHECK(entry->independent_copies);
  const Hopper::Config parsed =
      entry
          ->parse(ConfigNode::load_string("healthy_z_range: [0.5, .inf]\n"
                                          "healthy_state_range: [-.inf, 50]\n"
                                          "terminate_when_unhealthy: false\n",
                                          "exp.yaml"))
          .get<Hopper::Config>();
  CHECK(parsed.healthy_z_range == RangeKwarg{0.5, kInf});
  CHECK(parsed.healthy_state_range == RangeKwarg{-kInf, 50.0});
  CHECK_FALSE(parsed.terminate_when_unhealthy);
}

TEST_CASE("Hopper-v4: a step equals MuJoCo's C API stepped as Gymnasium does", "[mujoco]") {
  Hopper env;
  ReferenceSim sim("hopper.xml");
  std::vector<float> obs(11);
  env.reset(3, obs);
  // The same history as the env: MuJoCo's solver starts from the last state's accelerations
  // (qacc_warmstart), which set_state keeps, in Gymnasium as here.
  sim.set_state(env.qpos(), env.qvel());
  Rng rng(11);
  int unhealthy = 0, clipped = 0;
  for (int trial = 0; trial < 40; ++trial) {
    std::vector<double> qpos, qvel;
    random_hopper_state(rng, qpos, qvel);
    env.set_state(qpos, qvel);
    sim.set_state(qpos, qvel);
    const std::vector<float> action = random_controls(rng, 3, 1.5);

    const double x_before = sim.data().qpos[0];
    sim.step(action, 4);
    const StepResult r = env.step(action, obs);

    const mjData& d = sim.data();
    const double x_velocity = (d.qpos[0] - x_before) / (sim.model().opt.timestep * 4);
    const double ctrl_cost = 1e-3 * static_cast<double>(numpy_float32_sum_of_squares(action));
    const bool healthy = hopper_healthy(d);
    CHECK(r.reward == (x_velocity + 1.0) - ctrl_cost);
    CHECK(r.terminated == !healthy);
    CHECK_FALSE(r.truncated);
    for (int i = 0; i < 5; ++i) CHECK(obs[i] == static_cast<float>(d.qpos[i + 1]));
    for (int i = 0; i < 6; ++i) {
      CHECK(obs[5 + i] == static_cast<float>(std::clamp(d.qvel[i], -10.0, 10.0)));
      clipped += std::abs(d.qvel[i]) > 10.0;
    }
    CHECK(info_value(env, "x_position") == d.qpos[0]);
    CHECK(info_value(env, "x_velocity") == x_velocity);
    unhealthy += !healthy;
  }
  CHECK(unhealthy > 0);  // both rules' outcomes and the clip were exercised
  CHECK(unhealthy < 40);
  CHECK(clipped > 0);
}

TEST_CASE("Hopper-v4: the healthy ranges are open at both ends, and unhealthy ends the episode",
          "[mujoco]") {
  // One transition; its end state's z, angle and largest |state entry| become range bounds.
  std::vector<double> qpos{0.0, 1.2, 0.05, -0.1, -0.2, 0.1}, qvel{0.3, -0.5, 0.2, 1.0, -1.0, 0.5};
  const std::vector<float> action{0.3f, -0.6f, 0.9f};
  // Each env below is reset with seed 0, then set to this state: the reference goes through the
  // same states (the solver's warm start carries over set_state).
  Hopper after_reset;
  std::vector<float> reset_obs(11);
  after_reset.reset(0, reset_obs);
  ReferenceSim sim("hopper.xml");
  sim.set_state(after_reset.qpos(), after_reset.qvel());
  sim.set_state(qpos, qvel);
  sim.step(action, 4);
  const double z = sim.data().qpos[1], angle = sim.data().qpos[2];
  double largest = 0.0;
  for (int i = 2; i < 6; ++i) largest = std::max(largest, std::abs(sim.data().qpos[i]));
  for (int i = 0; i < 6; ++i) largest = std::max(largest, std::abs(sim.data().qvel[i]));
  REQUIRE(hopper_healthy(sim.data()));

  const auto step_with = [&](const Hopper::Config& config) {
    Hopper env(config);
    std::vector<float> obs(11);
    env.reset(0, obs);
    env.set_state(qpos, qvel);
    return env.step(action, obs);
  };
  const auto terminated_with = [&](auto&& change) {
    Hopper::Config config;
    change(config);
    return step_with(config).terminated;
  };
  const auto down = [](double v) { return std::nextafter(v, -kInf); };
  const auto up = [](double v) { return std::nextafter(v, kInf); };
  CHECK_FALSE(terminated_with([](Hopper::Config&) {}));
  CHECK(terminated_with([&](Hopper::Config& c) { c.healthy_z_range = {z, kInf}; }));
  CHECK_FALSE(terminated_with([&](Hopper::Config& c) { c.healthy_z_range = {down(z), kInf}; }));
  CHECK(terminated_with([&](Hopper::Config& c) { c.healthy_z_range = {0.0, z}; }));
  CHECK_FALSE(terminated_with([&](Hopper::Config& c) { c.healthy_z_range = {0.0, up(z)}; }));
  CHECK(terminated_with([&](Hopper::Config& c) { c.healthy_angle_range = {angle, 1.0}; }));
  CHECK_FALSE(terminated_with([&](Hopper::Config& c) {
    c.healthy_angle_range = {down(angle), 1.0};
  }));
  CHECK(terminated_with([&](Hopper::Config& c) { c.healthy_angle_range = {-1.0, angle}; }));
  CHECK_FALSE(terminated_with([&](Hopper::Config& c) {
    c.healthy_angle_range = {-1.0, up(angle)};
  }));
  CHECK(terminated_with([&](Hopper::Config& c) { c.healthy_state_range = {-largest, largest}; }));
  CHECK_FALSE(terminated_with([&](Hopper::Config& c) {
    c.healthy_state_range = {-up(largest), up(largest)};
  }));

  // terminate_when_unhealthy false: never terminated, and the healthy reward is
  // float(is_healthy or False) * healthy_reward: 0 when unhealthy (-0.0 for a negative weight).
  const double x_velocity = (sim.data().qpos[0] - qpos[0]) / (sim.model().opt.timestep * 4);
  const double ctrl_cost = 1e-3 * static_cast<double>(numpy_float32_sum_of_squares(action));
  Hopper::Config lenient;
  lenient.terminate_when_unhealthy = false;
  StepResult r = step_with(lenient);
  CHECK_FALSE(r.terminated);
  CHECK(r.reward == (x_velocity + 1.0) - ctrl_cost);
  lenient.healthy_z_range = {z, kInf};  // now unhealthy
  r = step_with(lenient);
  CHECK_FALSE(r.terminated);
  CHECK(r.reward == (x_velocity + 0.0) - ctrl_cost);
  lenient.healthy_reward = -2.0;
  CHECK(step_with(lenient).reward == (x_velocity + -0.0) - ctrl_cost);
  // With termination (the default), an unhealthy step still earns the healthy reward.
  Hopper::Config strict;
  strict.healthy_z_range = {z, kInf};
  r = step_with(strict);
  CHECK(r.terminated);
  CHECK(r.reward == (x_velocity + 1.0) - ctrl_cost);
}

TEST_CASE("Hopper-v4: a fallen hopper is terminated", "[mujoco]") {
  Hopper env;
  std::vector<float> obs(11);
  env.reset(0, obs);
  std::vector<double> qpos(env.init_qpos().begin(), env.init_qpos().end());
  qpos[1] = 0.3;  // the torso near the floor
  env.set_state(qpos, std::vector<double>(6, 0.0));
  CHECK(env.step(std::vector<float>(3, 0.0f), obs).terminated);
}

TEST_CASE("Hopper-v4: reset draws U(-scale, scale) for qpos, then for qvel", "[mujoco]") {
  Hopper::Config config;
  config.reset_noise_scale = 0.02;
  Hopper env(config);
  std::vector<float> obs(11);
  for (uint64_t seed = 0; seed < 20; ++seed) {
    env.reset(seed, obs);
    Rng expected(seed);  // the env's stream after reset(seed) (EnvSeeding)
    for (int i = 0; i < 6; ++i) {
      const double noise = expected.uniform(-0.02, 0.02);
      CHECK(env.qpos()[i] == env.init_qpos()[i] + noise);
    }
    for (int i = 0; i < 6; ++i) {
      const double noise = expected.uniform(-0.02, 0.02);
      CHECK(env.qvel()[i] == env.init_qvel()[i] + noise);
    }
    for (int i = 0; i < 5; ++i) CHECK(obs[i] == static_cast<float>(env.qpos()[i + 1]));
    for (int i = 0; i < 6; ++i) CHECK(obs[5 + i] == static_cast<float>(env.qvel()[i]));
  }
}
