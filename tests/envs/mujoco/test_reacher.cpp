// Reacher-v4 (gymnasium/envs/mujoco/reacher_v4.py): spaces, transitions (the reward measured
// before the step is simulated) and info against the tests' own MuJoCo stepping, and the reset's
// draws: the arm's noise, the target sampled until it lies within 0.2 of the centre, qvel.
#include <catch2/catch.hpp>
#include <cmath>
#include <vector>

#include "envs/mujoco/mujoco_reference.hpp"
#include "envs/mujoco/mujoco_task_test.hpp"
#include "rlrun/envs/mujoco/reacher.hpp"
#include "rlrun/runtime/components/builtins.hpp"
#include "rlrun/runtime/components/registry.hpp"

using namespace rlrun;
using namespace rlrun::testing;
using rlrun::mujoco::Reacher;

namespace {

// get_body_com("fingertip") - get_body_com("target"): data.xpos as the simulation left it.
std::vector<double> fingertip_to_target(const ReferenceSim& sim) {
  const double* tip = sim.data().xpos + 3 * sim.body("fingertip");
  const double* target = sim.data().xpos + 3 * sim.body("target");
  return {tip[0] - target[0], tip[1] - target[1], tip[2] - target[2]};
}

}  // namespace

TEST_CASE("Reacher-v4: Gymnasium's spaces and time limit", "[mujoco]") {
  Reacher env;
  CHECK(env.id() == "Reacher-v4");
  CHECK(env.observation_space().shape() == std::vector<int>{11});
  CHECK(env.action_space().shape() == std::vector<int>{2});
  CHECK(env.action_space().low() == std::vector<float>(2, -1.0f));
  CHECK(env.action_space().high() == std::vector<float>(2, 1.0f));
  CHECK(env.frame_skip() == 2);
  CHECK(env.dt() == 0.01 * 2);
  CHECK(env.init_qpos()[2] == 0.1);  // the target's slides rest at their ref
  CHECK(env.init_qpos()[3] == -0.1);
  const EnvEntry* entry = builtin_registry().find_env("Reacher-v4");
  REQUIRE(entry);
  CHECK(entry->max_episode_steps == 50);
  CHECK(entry->independent_copies);
}

TEST_CASE("Reacher-v4: a step equals MuJoCo's C API stepped as Gymnasium does", "[mujoco]") {
  Reacher env;
  ReferenceSim sim("reacher.xml");
  std::vector<float> obs(11);
  env.reset(3, obs);
  // The same history as the env: MuJoCo's solver starts from the last state's accelerations
  // (qacc_warmstart), which set_state keeps, in Gymnasium as here.
  sim.set_state(env.qpos(), env.qvel());
  Rng rng(16);
  for (int trial = 0; trial < 15; ++trial) {
    std::vector<double> qpos{rng.uniform(-3.2, 3.2), rng.uniform(-2.9, 2.9), rng.uniform(-0.2, 0.2),
                             rng.uniform(-0.2, 0.2)};
    const std::vector<double> qvel = random_values(rng, 4, -3.0, 3.0);
    env.set_state(qpos, qvel);
    sim.set_state(qpos, qvel);
    // Several steps in a row: after the first, the positions the reward reads are those the
    // last physics step left in data.xpos (with RK4 not the new state's), as in Gymnasium.
    for (int step = 0; step < 3; ++step) {
      const std::vector<float> action = random_controls(rng, 2, 1.5);
      const double reward_dist = -numpy_norm(fingertip_to_target(sim));
      const double reward_ctrl = -static_cast<double>(numpy_float32_sum_of_squares(action));
      sim.step(action, 2);
      const StepResult r = env.step(action, obs);

      const mjData& d = sim.data();
      CHECK(r.reward == reward_dist + reward_ctrl);
      CHECK_FALSE(r.terminated);
      CHECK_FALSE(r.truncated);
      for (int i = 0; i < 2; ++i) {
        CHECK(obs[i] == static_cast<float>(std::cos(d.qpos[i])));
        CHECK(obs[2 + i] == static_cast<float>(std::sin(d.qpos[i])));
        CHECK(obs[4 + i] == static_cast<float>(d.qpos[2 + i]));
        CHECK(obs[6 + i] == static_cast<float>(d.qvel[i]));
      }
      const std::vector<double> vec = fingertip_to_target(sim);
      for (int i = 0; i < 3; ++i) CHECK(obs[8 + i] == static_cast<float>(vec[i]));
      CHECK(info_value(env, "reward_dist") == reward_dist);
      CHECK(info_value(env, "reward_ctrl") == reward_ctrl);
    }
  }
}

TEST_CASE("Reacher-v4: reset samples the target within 0.2 of the centre, after the arm's noise",
          "[mujoco]") {
  Reacher env;
  std::vector<float> obs(11);
  int rejected = 0;
  for (uint64_t seed = 0; seed < 100; ++seed) {
    env.reset(seed, obs);
    // The draws of reacher_v4.py's reset_model, in order, from the env's stream.
    Rng expected(seed);
    std::vector<double> qpos(4);
    for (int i = 0; i < 4; ++i) qpos[i] = expected.uniform(-0.1, 0.1) + env.init_qpos()[i];
    std::vector<double> goal;
    for (;;) {
      goal = {expected.uniform(-0.2, 0.2), expected.uniform(-0.2, 0.2)};
      if (numpy_norm(goal) < 0.2) break;
      ++rejected;
    }
    qpos[2] = goal[0];
    qpos[3] = goal[1];
    std::vector<double> qvel(4);
    for (int i = 0; i < 4; ++i) qvel[i] = env.init_qvel()[i] + expected.uniform(-0.005, 0.005);
    qvel[2] = qvel[3] = 0.0;
    for (int i = 0; i < 4; ++i) {
      CHECK(env.qpos()[i] == qpos[i]);
      CHECK(env.qvel()[i] == qvel[i]);
    }
    CHECK(std::hypot(env.qpos()[2], env.qpos()[3]) < 0.2);
    CHECK(obs[4] == static_cast<float>(goal[0]));
    CHECK(obs[5] == static_cast<float>(goal[1]));
  }
  CHECK(rejected > 0);  // the resampling ran (a draw outside the disc is 21 % likely)
}
