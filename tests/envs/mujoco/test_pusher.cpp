// Pusher-v4 (gymnasium/envs/mujoco/pusher_v4.py): spaces, transitions (the reward measured
// before the step is simulated) and info against the tests' own MuJoCo stepping, and the reset:
// the arm at rest, the cylinder sampled until it lies more than 0.17 from the goal, qvel's
// noise with the last four zero.
#include <catch2/catch.hpp>
#include <cmath>
#include <vector>

#include "envs/mujoco/mujoco_reference.hpp"
#include "envs/mujoco/mujoco_task_test.hpp"
#include "rlrun/envs/mujoco/pusher.hpp"
#include "rlrun/runtime/components/builtins.hpp"
#include "rlrun/runtime/components/registry.hpp"

using namespace rlrun;
using namespace rlrun::testing;
using rlrun::mujoco::Pusher;

namespace {

const double* body_com(const ReferenceSim& sim, const char* name) {
  return sim.data().xpos + 3 * sim.body(name);
}

std::vector<double> difference(const double* a, const double* b) {
  return {a[0] - b[0], a[1] - b[1], a[2] - b[2]};
}

}  // namespace

TEST_CASE("Pusher-v4: Gymnasium's spaces and time limit", "[mujoco]") {
  Pusher env;
  CHECK(env.id() == "Pusher-v4");
  CHECK(env.observation_space().shape() == std::vector<int>{23});
  CHECK(env.action_space().shape() == std::vector<int>{7});
  CHECK(env.action_space().low() == std::vector<float>(7, -2.0f));
  CHECK(env.action_space().high() == std::vector<float>(7, 2.0f));
  CHECK(env.frame_skip() == 5);
  CHECK(env.dt() == 0.01 * 5);
  const EnvEntry* entry = builtin_registry().find_env("Pusher-v4");
  REQUIRE(entry);
  CHECK(entry->max_episode_steps == 100);
  CHECK(entry->independent_copies);
}

TEST_CASE("Pusher-v4: a step equals MuJoCo's C API stepped as Gymnasium does", "[mujoco]") {
  Pusher env;
  ReferenceSim sim("pusher.xml");
  std::vector<float> obs(23);
  env.reset(3, obs);
  // The same history as the env: MuJoCo's solver starts from the last state's accelerations
  // (qacc_warmstart), which set_state keeps, in Gymnasium as here.
  sim.set_state(env.qpos(), env.qvel());
  Rng rng(17);
  for (int trial = 0; trial < 10; ++trial) {
    std::vector<double> qpos = random_values(rng, 11, -0.5, 0.5);
    for (int i = 7; i < 11; ++i) qpos[i] = rng.uniform(-0.3, 0.3);
    const std::vector<double> qvel = random_values(rng, 11, -1.0, 1.0);
    env.set_state(qpos, qvel);
    sim.set_state(qpos, qvel);
    // Several steps in a row: the reward reads the positions the last physics step computed.
    for (int step = 0; step < 3; ++step) {
      const std::vector<float> action = random_controls(rng, 7, 2.5);  // beyond [-2, 2] too
      const double reward_near =
          -numpy_norm(difference(body_com(sim, "object"), body_com(sim, "tips_arm")));
      const double reward_dist =
          -numpy_norm(difference(body_com(sim, "object"), body_com(sim, "goal")));
      const double reward_ctrl = -static_cast<double>(numpy_float32_sum_of_squares(action));
      sim.step(action, 5);
      const StepResult r = env.step(action, obs);

      const mjData& d = sim.data();
      CHECK(r.reward == reward_dist + 0.1 * reward_ctrl + 0.5 * reward_near);
      CHECK_FALSE(r.terminated);
      CHECK_FALSE(r.truncated);
      for (int i = 0; i < 7; ++i) {
        CHECK(obs[i] == static_cast<float>(d.qpos[i]));
        CHECK(obs[7 + i] == static_cast<float>(d.qvel[i]));
      }
      const char* bodies[] = {"tips_arm", "object", "goal"};
      for (int b = 0; b < 3; ++b)
        for (int i = 0; i < 3; ++i)
          CHECK(obs[14 + 3 * b + i] == static_cast<float>(body_com(sim, bodies[b])[i]));
      CHECK(info_value(env, "reward_dist") == reward_dist);
      CHECK(info_value(env, "reward_ctrl") == reward_ctrl);
    }
  }
}

TEST_CASE("Pusher-v4: reset samples the cylinder more than 0.17 from the goal, arm at rest",
          "[mujoco]") {
  Pusher env;
  std::vector<float> obs(23);
  const std::vector<double> rest(env.init_qpos().begin(), env.init_qpos().end());
  int rejected = 0;
  for (uint64_t seed = 0; seed < 100; ++seed) {
    env.reset(seed, obs);
    // The draws of pusher_v4.py's reset_model, in order, from the env's stream.
    Rng expected(seed);
    std::vector<double> cylinder;
    for (;;) {
      cylinder = {expected.uniform(-0.3, 0.0), expected.uniform(-0.2, 0.2)};
      if (numpy_norm(std::vector{cylinder[0] - 0.0, cylinder[1] - 0.0}) > 0.17) break;
      ++rejected;
    }
    std::vector<double> qvel(11);
    for (int i = 0; i < 11; ++i) qvel[i] = env.init_qvel()[i] + expected.uniform(-0.005, 0.005);
    for (int i = 7; i < 11; ++i) qvel[i] = 0.0;
    for (int i = 0; i < 7; ++i) CHECK(env.qpos()[i] == rest[i]);  // no noise on the arm
    CHECK(env.qpos()[7] == cylinder[0]);
    CHECK(env.qpos()[8] == cylinder[1]);
    CHECK(env.qpos()[9] == 0.0);  // the goal
    CHECK(env.qpos()[10] == 0.0);
    CHECK(std::hypot(env.qpos()[7], env.qpos()[8]) > 0.17);
    for (int i = 0; i < 11; ++i) CHECK(env.qvel()[i] == qvel[i]);
    // Gymnasium writes the cylinder into init_qpos itself (an alias); rlrun's stays the rest pose.
    for (int i = 0; i < 11; ++i) CHECK(env.init_qpos()[i] == rest[i]);
  }
  CHECK(rejected > 0);  // the resampling ran (a draw within 0.17 is 38 % likely)
}
