// InvertedPendulum-v4 (gymnasium/envs/mujoco/inverted_pendulum_v4.py): spaces, transitions and
// the termination rule against the tests' own MuJoCo stepping, and the reset noise.
#include <catch2/catch.hpp>
#include <cmath>
#include <vector>

#include "envs/mujoco/mujoco_reference.hpp"
#include "envs/mujoco/mujoco_task_test.hpp"
#include "rlrun/envs/mujoco/inverted_pendulum.hpp"
#include "rlrun/runtime/components/builtins.hpp"
#include "rlrun/runtime/components/registry.hpp"

using namespace rlrun;
using namespace rlrun::testing;
using rlrun::mujoco::InvertedPendulum;

TEST_CASE("InvertedPendulum-v4: Gymnasium's spaces and time limit", "[mujoco]") {
  InvertedPendulum env;
  CHECK(env.id() == "InvertedPendulum-v4");
  CHECK(env.observation_space().shape() == std::vector<int>{4});
  CHECK(env.action_space().shape() == std::vector<int>{1});
  CHECK(env.action_space().low() == std::vector<float>{-3.0f});
  CHECK(env.action_space().high() == std::vector<float>{3.0f});
  CHECK(env.frame_skip() == 2);
  CHECK(env.dt() == 0.02 * 2);
  CHECK(env.info().keys().empty());  // Gymnasium's info is {}
  const EnvEntry* entry = builtin_registry().find_env("InvertedPendulum-v4");
  REQUIRE(entry);
  CHECK(entry->max_episode_steps == 1000);
  CHECK(entry->independent_copies);
  // The v4 constructor has no task kwargs: only xml_file (rlrun's) is known.
  CHECK_THROWS_WITH(entry->parse(ConfigNode::load_string("reset_noise_scale: 0.1", "exp.yaml")),
                    Catch::Contains("unknown key 'reset_noise_scale'"));
}

TEST_CASE("InvertedPendulum-v4: a step equals MuJoCo's C API stepped as Gymnasium does",
          "[mujoco]") {
  InvertedPendulum env;
  ReferenceSim sim("inverted_pendulum.xml");
  std::vector<float> obs(4);
  env.reset(3, obs);
  // The same history as the env: MuJoCo's solver starts from the last state's accelerations
  // (qacc_warmstart), which set_state keeps, in Gymnasium as here.
  sim.set_state(env.qpos(), env.qvel());
  Rng rng(14);
  int terminated = 0;
  for (int trial = 0; trial < 60; ++trial) {
    // Pole angles around the 0.2 rad limit and well inside it.
    const std::vector<double> qpos{rng.uniform(-0.9, 0.9), rng.uniform(-0.25, 0.25)};
    const std::vector<double> qvel = random_values(rng, 2, -0.5, 0.5);
    env.set_state(qpos, qvel);
    sim.set_state(qpos, qvel);
    const std::vector<float> action = random_controls(rng, 1, 4.5);  // beyond [-3, 3] too
    sim.step(action, 2);
    const StepResult r = env.step(action, obs);

    const mjData& d = sim.data();
    bool finite = true;
    for (int i = 0; i < 2; ++i)
      finite = finite && std::isfinite(d.qpos[i]) && std::isfinite(d.qvel[i]);
    const bool expected_terminated = !finite || std::abs(d.qpos[1]) > 0.2;
    CHECK(r.reward == 1.0);  // also on the step that terminates
    CHECK(r.terminated == expected_terminated);
    CHECK_FALSE(r.truncated);
    for (int i = 0; i < 2; ++i) CHECK(obs[i] == static_cast<float>(d.qpos[i]));
    for (int i = 0; i < 2; ++i) CHECK(obs[2 + i] == static_cast<float>(d.qvel[i]));
    terminated += expected_terminated;
  }
  CHECK(terminated > 0);
  CHECK(terminated < 60);
}

TEST_CASE("InvertedPendulum-v4: reset draws U(-0.01, 0.01) for qpos, then for qvel", "[mujoco]") {
  InvertedPendulum env;
  std::vector<float> obs(4);
  for (uint64_t seed = 0; seed < 20; ++seed) {
    env.reset(seed, obs);
    Rng expected(seed);
    for (int i = 0; i < 2; ++i) {
      const double noise = expected.uniform(-0.01, 0.01);
      CHECK(env.qpos()[i] == env.init_qpos()[i] + noise);
    }
    for (int i = 0; i < 2; ++i) {
      const double noise = expected.uniform(-0.01, 0.01);
      CHECK(env.qvel()[i] == env.init_qvel()[i] + noise);
    }
    CHECK(obs[1] == static_cast<float>(env.qpos()[1]));
  }
}
