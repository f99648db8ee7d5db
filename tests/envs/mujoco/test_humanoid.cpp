// Humanoid-v4 (gymnasium/envs/mujoco/humanoid_v4.py): spaces, kwargs and time limit;
// transitions equal the tests' own MuJoCo stepping with humanoid_v4.py's formulas written here;
// the healthy rule at its (excluded) bounds; reset noise.
#include <array>
#include <catch2/catch.hpp>
#include <cmath>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "envs/mujoco/mujoco_reference.hpp"
#include "envs/mujoco/mujoco_task_test.hpp"
#include "rlrun/core/config_node.hpp"
#include "rlrun/envs/mujoco/humanoid.hpp"
#include "rlrun/runtime/components/builtins.hpp"
#include "rlrun/runtime/components/registry.hpp"
#include "rlrun/state.hpp"

using namespace rlrun;
using namespace rlrun::testing;
using rlrun::mujoco::Humanoid;

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// humanoid_v4.py's mass_center: (np.sum(mass * xipos, axis=0) / np.sum(mass))[0:2], the axis-0
// sum row after row (as NumPy 1.24 computes it), the total mass pairwise.
std::array<double, 2> mass_center(const ReferenceSim& sim) {
  const mjModel& m = sim.model();
  const double total =
      numpy_sum<double>(std::span<const double>(m.body_mass, static_cast<size_t>(m.nbody)));
  std::array<double, 2> sum{0.0, 0.0};
  for (int b = 0; b < m.nbody; ++b)
    for (int j = 0; j < 2; ++j) sum[j] += m.body_mass[b] * sim.data().xipos[3 * b + j];
  return {sum[0] / total, sum[1] / total};
}

// cinert, cvel, qfrc_actuator, cfrc_ext: the observation's part after qpos and qvel.
void put_body_dynamics(const ReferenceSim& sim, std::vector<float>& obs) {
  const mjModel& m = sim.model();
  const mjData& d = sim.data();
  for (int i = 0; i < 10 * m.nbody; ++i) obs.push_back(static_cast<float>(d.cinert[i]));
  for (int i = 0; i < 6 * m.nbody; ++i) obs.push_back(static_cast<float>(d.cvel[i]));
  for (int i = 0; i < m.nv; ++i) obs.push_back(static_cast<float>(d.qfrc_actuator[i]));
  for (int i = 0; i < 6 * m.nbody; ++i) obs.push_back(static_cast<float>(d.cfrc_ext[i]));
}

struct Expected {
  std::vector<float> obs;
  double reward = 0.0;
  bool terminated = false;
  std::vector<std::pair<std::string, double>> info;
};

Expected humanoid_step(ReferenceSim& sim, const Humanoid::Config& c,
                       const std::vector<float>& action) {
  const std::array<double, 2> before = mass_center(sim);
  sim.step(action, 5);
  const std::array<double, 2> after = mass_center(sim);
  const double dt = 0.003 * 5;
  const double vx = (after[0] - before[0]) / dt, vy = (after[1] - before[1]) / dt;
  const double ctrl_cost =
      c.ctrl_cost_weight *
      numpy_sum_of_squares<double>({sim.data().ctrl, static_cast<size_t>(sim.model().nu)});
  const double forward_reward = c.forward_reward_weight * vx;
  const double z = sim.data().qpos[2];
  const bool healthy = c.healthy_z_range.low < z && z < c.healthy_z_range.high;
  const double healthy_reward =
      (healthy || c.terminate_when_unhealthy ? 1.0 : 0.0) * c.healthy_reward;

  Expected e;
  const std::vector<double> qpos = sim.qpos(), qvel = sim.qvel();
  for (size_t i = c.exclude_current_positions_from_observation ? 2 : 0; i < qpos.size(); ++i)
    e.obs.push_back(static_cast<float>(qpos[i]));
  for (double v : qvel) e.obs.push_back(static_cast<float>(v));
  put_body_dynamics(sim, e.obs);
  e.reward = (forward_reward + healthy_reward) - ctrl_cost;
  e.terminated = c.terminate_when_unhealthy && !healthy;
  e.info = {{"reward_linvel", forward_reward},
            {"reward_quadctrl", -ctrl_cost},
            {"reward_alive", healthy_reward},
            {"x_position", after[0]},
            {"y_position", after[1]},
            {"distance_from_origin", std::sqrt(after[0] * after[0] + after[1] * after[1])},
            {"x_velocity", vx},
            {"y_velocity", vy},
            {"forward_reward", forward_reward}};
  return e;
}

void check_transitions(const Humanoid::Config& config, uint64_t seed) {
  Humanoid env(config);
  ReferenceSim sim("humanoid.xml");
  std::vector<float> obs(env.observation_space().shape()[0]);
  env.reset(seed, obs);
  // The reference starts where the env's reset left MuJoCo: mj_forward also leaves the solver's
  // warm start (qacc_warmstart) behind, which the next states' solutions start from.
  sim.set_state(env.qpos(), env.qvel());
  Rng rng(seed);
  for (int trial = 0; trial < 6; ++trial) {
    std::vector<double> qpos = around(env.init_qpos(), 0.2, rng);
    const std::vector<double> qvel = around(env.init_qvel(), 1.0, rng);
    qpos[2] = rng.uniform(0.8, 2.2);  // above, inside and below the healthy range
    env.set_state(qpos, qvel);
    sim.set_state(qpos, qvel);
    for (int step = 0; step < 3; ++step) {
      const std::vector<float> action = random_controls(rng, 17, 0.6);  // beyond ctrlrange too
      const Expected e = humanoid_step(sim, config, action);
      const StepResult r = env.step(action, obs);
      INFO("trial " << trial << " step " << step);
      CHECK(obs == e.obs);
      CHECK(r.reward == e.reward);
      CHECK(r.terminated == e.terminated);
      CHECK_FALSE(r.truncated);
      check_info(env.info(), e.info);
    }
  }
}

}  // namespace

TEST_CASE("Humanoid-v4: Gymnasium's spaces, kwargs and time limit", "[mujoco]") {
  Humanoid env;
  CHECK(env.id() == "Humanoid-v4");
  CHECK(env.observation_space().shape() == std::vector<int>{376});
  CHECK(env.action_space().shape() == std::vector<int>{17});
  CHECK(env.action_space().low() == std::vector<float>(17, -0.4f));
  CHECK(env.action_space().high() == std::vector<float>(17, 0.4f));
  CHECK(env.dt() == 0.003 * 5);
  CHECK(env.frame_skip() == 5);
  Humanoid::Config config;
  config.exclude_current_positions_from_observation = false;
  CHECK(Humanoid(config).observation_space().shape() == std::vector<int>{378});

  const EnvEntry* entry = builtin_registry().find_env("Humanoid-v4");
  REQUIRE(entry);
  CHECK(entry->max_episode_steps == 1000);
  CHECK(entry->independent_copies);
  const Humanoid::Config defaults = entry->parse(ConfigNode{}).get<Humanoid::Config>();
  CHECK(defaults.forward_reward_weight == 1.25);
  CHECK(defaults.ctrl_cost_weight == 0.1);
  CHECK(defaults.healthy_reward == 5.0);
  CHECK(defaults.terminate_when_unhealthy);
  CHECK(defaults.healthy_z_range == mujoco::RangeKwarg{1.0, 2.0});
  CHECK(defaults.reset_noise_scale == 1e-2);
  CHECK(defaults.exclude_current_positions_from_observation);
  const Humanoid::Config set =
      entry->parse(ConfigNode::load_string("{healthy_z_range: [0.8, .inf]}", "test.yaml"))
          .get<Humanoid::Config>();
  CHECK(set.healthy_z_range == mujoco::RangeKwarg{0.8, kInf});
}

TEST_CASE("Humanoid-v4: a step equals MuJoCo's C API stepped as Gymnasium does", "[mujoco]") {
  Humanoid::Config config;
  SECTION("defaults") { check_transitions(config, 1); }
  SECTION("positions observed, other weights, terminate_when_unhealthy false") {
    config.exclude_current_positions_from_observation = false;
    config.forward_reward_weight = 2.0;
    config.ctrl_cost_weight = 0.3;
    config.healthy_reward = 1.5;
    config.terminate_when_unhealthy = false;
    check_transitions(config, 2);
  }
}

TEST_CASE("Humanoid-v4: the healthy range excludes its bounds", "[mujoco]") {
  const std::vector<float> action(17, 0.2f);
  ReferenceSim sim("humanoid.xml");
  const std::vector<double> qpos = sim.qpos(), qvel(23, 0.0);
  sim.set_state(qpos, qvel);
  sim.step(action, 5);
  const double z = sim.data().qpos[2];
  const auto step_with = [&](double low, double high, bool terminate) {
    Humanoid::Config config;
    config.healthy_z_range = {low, high};
    config.terminate_when_unhealthy = terminate;
    Humanoid env(config);
    std::vector<float> obs(376);
    env.reset(0, obs);
    env.set_state(qpos, qvel);
    const StepResult r = env.step(action, obs);
    REQUIRE(env.qpos()[2] == z);
    return std::pair(r.terminated, env.info().get(env.info().find("reward_alive")));
  };
  CHECK(step_with(z, 2.0, true) == std::pair(true, 5.0));
  CHECK(step_with(1.0, z, true) == std::pair(true, 5.0));
  CHECK(step_with(std::nextafter(z, 0.0), 2.0, true) == std::pair(false, 5.0));
  CHECK(step_with(1.0, std::nextafter(z, kInf), true) == std::pair(false, 5.0));
  // Unhealthy without termination: the episode goes on and the healthy reward is not paid.
  CHECK(step_with(z, 2.0, false) == std::pair(false, 0.0));
  CHECK(step_with(-kInf, kInf, false) == std::pair(false, 5.0));
}

TEST_CASE("Humanoid-v4: reset draws uniform noise on qpos, then on qvel", "[mujoco]") {
  Humanoid env;
  std::vector<float> obs(376);
  ReferenceSim sim("humanoid.xml");
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
  CHECK(env.init_qpos()[2] == 1.4);
}

TEST_CASE("Humanoid-v4: a saved state resumes bit for bit (the PGS solver's warm start too)",
          "[mujoco]") {
  Humanoid env, copy;
  std::vector<float> obs(376), obs_copy(376);
  env.reset(1, obs);
  copy.reset(2, obs_copy);
  Rng rng(5);
  for (int i = 0; i < 20; ++i) env.step(random_controls(rng, 17, 0.4), obs);
  TensorMap tensors;
  StateWriter writer(tensors, "env.");
  env.write_state(writer);
  copy.read_state(StateReader(tensors, "env."));
  for (int i = 0; i < 20; ++i) {
    const std::vector<float> action = random_controls(rng, 17, 0.4);
    const StepResult a = env.step(action, obs);
    const StepResult b = copy.step(action, obs_copy);
    CHECK(a.reward == b.reward);
    CHECK(a.terminated == b.terminated);
    CHECK(obs == obs_copy);
    CHECK(env.info().values() == copy.info().values());
  }
}
