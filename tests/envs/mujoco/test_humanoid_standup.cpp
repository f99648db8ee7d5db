// HumanoidStandup-v4 (gymnasium/envs/mujoco/humanoidstandup_v4.py): spaces and time limit;
// transitions equal the tests' own MuJoCo stepping with humanoidstandup_v4.py's formulas written
// here, the impact cost's cap of 10 included; reset noise.
#include <algorithm>
#include <catch2/catch.hpp>
#include <string>
#include <utility>
#include <vector>

#include "envs/mujoco/mujoco_reference.hpp"
#include "envs/mujoco/mujoco_task_test.hpp"
#include "rlrun/envs/mujoco/humanoid_standup.hpp"
#include "rlrun/runtime/components/builtins.hpp"
#include "rlrun/runtime/components/registry.hpp"

using namespace rlrun;
using namespace rlrun::testing;
using rlrun::mujoco::HumanoidStandup;

namespace {

struct Expected {
  std::vector<float> obs;
  double reward = 0.0;
  double impact_cost = 0.0;
  std::vector<std::pair<std::string, double>> info;
};

Expected standup_step(ReferenceSim& sim, const std::vector<float>& action) {
  sim.step(action, 5);
  const mjModel& m = sim.model();
  const mjData& d = sim.data();
  const double uph_cost = (d.qpos[2] - 0) / 0.003;
  const double quad_ctrl_cost =
      0.1 * numpy_sum_of_squares<double>({d.ctrl, static_cast<size_t>(m.nu)});
  double quad_impact_cost =
      0.5e-6 * numpy_sum_of_squares<double>({d.cfrc_ext, static_cast<size_t>(6 * m.nbody)});
  if (10 < quad_impact_cost) quad_impact_cost = 10;  // Python's min(cost, 10)

  Expected e;
  for (int i = 2; i < m.nq; ++i) e.obs.push_back(static_cast<float>(d.qpos[i]));
  for (int i = 0; i < m.nv; ++i) e.obs.push_back(static_cast<float>(d.qvel[i]));
  for (int i = 0; i < 10 * m.nbody; ++i) e.obs.push_back(static_cast<float>(d.cinert[i]));
  for (int i = 0; i < 6 * m.nbody; ++i) e.obs.push_back(static_cast<float>(d.cvel[i]));
  for (int i = 0; i < m.nv; ++i) e.obs.push_back(static_cast<float>(d.qfrc_actuator[i]));
  for (int i = 0; i < 6 * m.nbody; ++i) e.obs.push_back(static_cast<float>(d.cfrc_ext[i]));
  e.reward = uph_cost - quad_ctrl_cost - quad_impact_cost + 1;
  e.impact_cost = quad_impact_cost;
  e.info = {{"reward_linup", uph_cost},
            {"reward_quadctrl", -quad_ctrl_cost},
            {"reward_impact", -quad_impact_cost}};
  return e;
}

}  // namespace

TEST_CASE("HumanoidStandup-v4: Gymnasium's spaces and time limit", "[mujoco]") {
  HumanoidStandup env;
  CHECK(env.id() == "HumanoidStandup-v4");
  CHECK(env.observation_space().shape() == std::vector<int>{376});
  CHECK(env.action_space().shape() == std::vector<int>{17});
  CHECK(env.action_space().low() == std::vector<float>(17, -0.4f));
  CHECK(env.action_space().high() == std::vector<float>(17, 0.4f));
  CHECK(env.dt() == 0.003 * 5);
  CHECK(env.frame_skip() == 5);
  const EnvEntry* entry = builtin_registry().find_env("HumanoidStandup-v4");
  REQUIRE(entry);
  CHECK(entry->max_episode_steps == 1000);
  CHECK(entry->independent_copies);
  CHECK(entry->params().size() == 1);  // xml_file only: Gymnasium's v4 task has no kwargs
}

TEST_CASE("HumanoidStandup-v4: a step equals MuJoCo's C API stepped as Gymnasium does",
          "[mujoco]") {
  HumanoidStandup env;
  ReferenceSim sim("humanoidstandup.xml");
  std::vector<float> obs(376);
  env.reset(1, obs);
  // The reference starts where the env's reset left MuJoCo: mj_forward also leaves the solver's
  // warm start (qacc_warmstart) behind, which the next states' solutions start from.
  sim.set_state(env.qpos(), env.qvel());
  Rng rng(1);
  bool capped = false, uncapped = false;
  for (int trial = 0; trial < 8; ++trial) {
    // Random states; some start deep inside the floor, whose contact forces exceed the impact
    // cost's cap.
    std::vector<double> qpos = around(env.init_qpos(), 0.2, rng);
    const std::vector<double> qvel = around(env.init_qvel(), 1.0, rng);
    qpos[2] = rng.uniform(-0.8, 0.6);
    env.set_state(qpos, qvel);
    sim.set_state(qpos, qvel);
    for (int step = 0; step < 3; ++step) {
      const std::vector<float> action = random_controls(rng, 17, 0.6);  // beyond ctrlrange too
      const Expected e = standup_step(sim, action);
      const StepResult r = env.step(action, obs);
      INFO("trial " << trial << " step " << step);
      CHECK(obs == e.obs);
      CHECK(r.reward == e.reward);
      CHECK_FALSE(r.terminated);
      CHECK_FALSE(r.truncated);
      check_info(env.info(), e.info);
      (e.impact_cost == 10 ? capped : uncapped) = true;
    }
  }
  CHECK(capped);
  CHECK(uncapped);
}

TEST_CASE("HumanoidStandup-v4: reset draws uniform noise on qpos, then on qvel", "[mujoco]") {
  HumanoidStandup env;
  std::vector<float> obs(376);
  ReferenceSim sim("humanoidstandup.xml");
  for (uint64_t seed : {5u, 6u}) {
    env.reset(seed, obs);
    // The reset_model with this seed's stream: nq uniform draws, then nv more, given to
    // set_state (whose mj_forward normalises the free joint's quaternion in qpos).
    Rng draws(seed);
    std::vector<double> qpos(env.init_qpos().begin(), env.init_qpos().end());
    std::vector<double> qvel(env.init_qvel().begin(), env.init_qvel().end());
    for (double& q : qpos) q += draws.uniform(-0.01, 0.01);
    for (double& v : qvel) v += draws.uniform(-0.01, 0.01);
    sim.set_state(qpos, qvel);
    CHECK(std::vector<double>(env.qpos().begin(), env.qpos().end()) == sim.qpos());
    CHECK(std::vector<double>(env.qvel().begin(), env.qvel().end()) == sim.qvel());
    CHECK(obs[0] == static_cast<float>(sim.qpos()[2]));
  }
  CHECK(env.init_qpos()[2] == 0.105);
}
