// InvertedDoublePendulum-v4 (gymnasium/envs/mujoco/inverted_double_pendulum_v4.py): spaces,
// transitions, reward and termination against the tests' own MuJoCo stepping and Gymnasium's
// formulas (NumPy float64 scalars: x**2 is pow), and the reset noise.
#include <catch2/catch.hpp>
#include <cmath>
#include <vector>

#include "envs/mujoco/mujoco_reference.hpp"
#include "envs/mujoco/mujoco_task_test.hpp"
#include "rlrun/envs/mujoco/inverted_double_pendulum.hpp"
#include "rlrun/runtime/components/builtins.hpp"
#include "rlrun/runtime/components/registry.hpp"

using namespace rlrun;
using namespace rlrun::testing;
using rlrun::mujoco::InvertedDoublePendulum;

TEST_CASE("InvertedDoublePendulum-v4: Gymnasium's spaces and time limit", "[mujoco]") {
  InvertedDoublePendulum env;
  CHECK(env.id() == "InvertedDoublePendulum-v4");
  CHECK(env.observation_space().shape() == std::vector<int>{11});
  CHECK(env.action_space().shape() == std::vector<int>{1});
  CHECK(env.action_space().low() == std::vector<float>{-1.0f});
  CHECK(env.action_space().high() == std::vector<float>{1.0f});
  CHECK(env.frame_skip() == 5);
  CHECK(env.dt() == 0.01 * 5);
  CHECK(env.info().keys().empty());  // Gymnasium's info is {}
  const EnvEntry* entry = builtin_registry().find_env("InvertedDoublePendulum-v4");
  REQUIRE(entry);
  CHECK(entry->max_episode_steps == 1000);
  CHECK(entry->independent_copies);
}

TEST_CASE("InvertedDoublePendulum-v4: a step equals MuJoCo's C API stepped as Gymnasium does",
          "[mujoco]") {
  InvertedDoublePendulum env;
  ReferenceSim sim("inverted_double_pendulum.xml");
  std::vector<float> obs(11);
  env.reset(3, obs);
  // The same history as the env: MuJoCo's solver starts from the last state's accelerations
  // (qacc_warmstart), which set_state keeps, in Gymnasium as here.
  sim.set_state(env.qpos(), env.qvel());
  Rng rng(15);
  int terminated = 0, clipped_velocity = 0, clipped_constraint = 0;
  for (int trial = 0; trial < 60; ++trial) {
    // The cart anywhere on its rail (its limit pushes back near +-1: constraint forces), poles
    // from upright to fallen (the tip's height y from 1.2 down past the limit of 1).
    const std::vector<double> qpos{rng.uniform(-1.05, 1.05), rng.uniform(-0.8, 0.8),
                                   rng.uniform(-0.8, 0.8)};
    const std::vector<double> qvel = random_values(rng, 3, -12.0, 12.0);
    env.set_state(qpos, qvel);
    sim.set_state(qpos, qvel);
    const std::vector<float> action = random_controls(rng, 1, 1.5);
    sim.step(action, 5);
    const StepResult r = env.step(action, obs);

    const mjData& d = sim.data();
    const double x = d.site_xpos[0], y = d.site_xpos[2];
    const double dist_penalty = 0.01 * numpy_scalar_pow2(x) + numpy_scalar_pow2(y - 2);
    const double v1 = d.qvel[1], v2 = d.qvel[2];
    const double vel_penalty = 1e-3 * numpy_scalar_pow2(v1) + 5e-3 * numpy_scalar_pow2(v2);
    CHECK(r.reward == 10 - dist_penalty - vel_penalty);
    CHECK(r.terminated == (y <= 1));
    CHECK_FALSE(r.truncated);
    CHECK(obs[0] == static_cast<float>(d.qpos[0]));
    for (int i = 0; i < 2; ++i) {
      CHECK(obs[1 + i] == static_cast<float>(std::sin(d.qpos[1 + i])));
      CHECK(obs[3 + i] == static_cast<float>(std::cos(d.qpos[1 + i])));
    }
    for (int i = 0; i < 3; ++i) {
      CHECK(obs[5 + i] == static_cast<float>(std::clamp(d.qvel[i], -10.0, 10.0)));
      CHECK(obs[8 + i] == static_cast<float>(std::clamp(d.qfrc_constraint[i], -10.0, 10.0)));
      clipped_velocity += std::abs(d.qvel[i]) > 10.0;
      clipped_constraint += std::abs(d.qfrc_constraint[i]) > 10.0;
    }
    terminated += y <= 1;
  }
  CHECK(terminated > 0);
  CHECK(terminated < 60);
  CHECK(clipped_velocity > 0);
  CHECK(clipped_constraint > 0);
}

TEST_CASE(
    "InvertedDoublePendulum-v4: reset draws U(-0.1, 0.1) for qpos, then 0.1 * N(0, 1) "
    "for qvel",
    "[mujoco]") {
  InvertedDoublePendulum env;
  std::vector<float> obs(11);
  for (uint64_t seed = 0; seed < 20; ++seed) {
    env.reset(seed, obs);
    Rng expected(seed);
    for (int i = 0; i < 3; ++i) {
      const double noise = expected.uniform(-0.1, 0.1);
      CHECK(env.qpos()[i] == env.init_qpos()[i] + noise);
    }
    for (int i = 0; i < 3; ++i) {
      const double noise = expected.normal() * 0.1;
      CHECK(env.qvel()[i] == env.init_qvel()[i] + noise);
    }
    CHECK(obs[0] == static_cast<float>(env.qpos()[0]));
  }
}
