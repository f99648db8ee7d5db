// Ant-v4 (gymnasium/envs/mujoco/ant_v4.py): spaces, kwargs and time limit; transitions equal the
// tests' own MuJoCo stepping with ant_v4.py's formulas written here; the healthy rule at its
// bounds; contact forces; reset noise.
#include <catch2/catch.hpp>
#include <cmath>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "envs/mujoco/mujoco_reference.hpp"
#include "envs/mujoco/mujoco_task_test.hpp"
#include "rlrun/core/config_node.hpp"
#include "rlrun/core/errors.hpp"
#include "rlrun/envs/mujoco/ant.hpp"
#include "rlrun/runtime/components/builtins.hpp"
#include "rlrun/runtime/components/registry.hpp"
#include "rlrun/state.hpp"

using namespace rlrun;
using namespace rlrun::testing;
using rlrun::mujoco::Ant;

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

struct Expected {
  std::vector<float> obs;
  double reward = 0.0;
  bool terminated = false;
  std::vector<std::pair<std::string, double>> info;
};

// ant_v4.py's step, from the reference simulation: xy of the torso body's xpos before and after
// do_simulation, the rewards and costs, the observation and info.
Expected ant_step(ReferenceSim& sim, const Ant::Config& c, const std::vector<float>& action) {
  const int torso = sim.body("torso");
  const double x0 = sim.data().xpos[3 * torso], y0 = sim.data().xpos[3 * torso + 1];
  sim.step(action, 5);
  const double x1 = sim.data().xpos[3 * torso], y1 = sim.data().xpos[3 * torso + 1];
  const double dt = 0.01 * 5;
  const double vx = (x1 - x0) / dt, vy = (y1 - y0) / dt;

  bool finite = true;
  for (double v : sim.qpos()) finite = finite && std::isfinite(v);
  for (double v : sim.qvel()) finite = finite && std::isfinite(v);
  const double z = sim.data().qpos[2];
  const bool healthy = finite && c.healthy_z_range.low <= z && z <= c.healthy_z_range.high;
  const double healthy_reward =
      (healthy || c.terminate_when_unhealthy ? 1.0 : 0.0) * c.healthy_reward;
  const double ctrl_cost =
      c.ctrl_cost_weight * static_cast<double>(numpy_sum_of_squares<float>(action));

  std::vector<double> clipped;
  for (int i = 0; i < 6 * sim.model().nbody; ++i)
    clipped.push_back(std::min(std::max(sim.data().cfrc_ext[i], c.contact_force_range.low),
                               c.contact_force_range.high));
  double costs = ctrl_cost, reward_ctrl = -ctrl_cost;
  if (c.use_contact_forces) {
    const double contact_cost = c.contact_cost_weight * numpy_sum_of_squares<double>(clipped);
    costs += contact_cost;
    reward_ctrl = -contact_cost;
  }

  Expected e;
  const std::vector<double> qpos = sim.qpos(), qvel = sim.qvel();
  for (size_t i = c.exclude_current_positions_from_observation ? 2 : 0; i < qpos.size(); ++i)
    e.obs.push_back(static_cast<float>(qpos[i]));
  for (double v : qvel) e.obs.push_back(static_cast<float>(v));
  if (c.use_contact_forces)
    for (double v : clipped) e.obs.push_back(static_cast<float>(v));
  e.reward = (vx + healthy_reward) - costs;
  e.terminated = c.terminate_when_unhealthy && !healthy;
  e.info = {{"reward_forward", vx},
            {"reward_ctrl", reward_ctrl},
            {"reward_survive", healthy_reward},
            {"x_position", x1},
            {"y_position", y1},
            {"distance_from_origin", std::sqrt(x1 * x1 + y1 * y1)},
            {"x_velocity", vx},
            {"y_velocity", vy},
            {"forward_reward", vx}};
  return e;
}

// Random states near the rest pose (some with the torso below the healthy range), three steps
// from each with random actions, also beyond ctrlrange: rlrun's step equals ant_step.
void check_transitions(const Ant::Config& config, uint64_t seed) {
  Ant env(config);
  ReferenceSim sim("ant.xml");
  std::vector<float> obs(env.observation_space().shape()[0]);
  env.reset(seed, obs);
  // The reference starts where the env's reset left MuJoCo: mj_forward also leaves the solver's
  // warm start (qacc_warmstart) behind, which the next states' solutions start from.
  sim.set_state(env.qpos(), env.qvel());
  Rng rng(seed);
  for (int trial = 0; trial < 8; ++trial) {
    std::vector<double> qpos = around(env.init_qpos(), 0.3, rng);
    const std::vector<double> qvel = around(env.init_qvel(), 2.0, rng);
    qpos[2] = rng.uniform(0.1, 1.2);  // above, inside and below the healthy range
    env.set_state(qpos, qvel);
    sim.set_state(qpos, qvel);
    for (int step = 0; step < 3; ++step) {
      const std::vector<float> action = random_controls(rng, 8, 1.3);
      const Expected e = ant_step(sim, config, action);
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

ConfigNode yaml(const std::string& text) { return ConfigNode::load_string(text, "test.yaml"); }

}  // namespace

TEST_CASE("Ant-v4: Gymnasium's spaces, kwargs and time limit", "[mujoco]") {
  Ant env;
  CHECK(env.id() == "Ant-v4");
  CHECK(env.observation_space().shape() == std::vector<int>{27});
  CHECK(env.action_space().shape() == std::vector<int>{8});
  CHECK(env.action_space().low() == std::vector<float>(8, -1.0f));
  CHECK(env.action_space().high() == std::vector<float>(8, 1.0f));
  CHECK(env.dt() == 0.01 * 5);
  CHECK(env.frame_skip() == 5);
  Ant::Config config;
  config.exclude_current_positions_from_observation = false;
  CHECK(Ant(config).observation_space().shape() == std::vector<int>{29});
  config.use_contact_forces = true;
  CHECK(Ant(config).observation_space().shape() == std::vector<int>{29 + 84});
  config.exclude_current_positions_from_observation = true;
  CHECK(Ant(config).observation_space().shape() == std::vector<int>{27 + 84});

  const EnvEntry* entry = builtin_registry().find_env("Ant-v4");
  REQUIRE(entry);
  CHECK(entry->max_episode_steps == 1000);
  CHECK(entry->independent_copies);
  const Ant::Config defaults = entry->parse(ConfigNode{}).get<Ant::Config>();
  CHECK(defaults.ctrl_cost_weight == 0.5);
  CHECK_FALSE(defaults.use_contact_forces);
  CHECK(defaults.contact_cost_weight == 5e-4);
  CHECK(defaults.healthy_reward == 1.0);
  CHECK(defaults.terminate_when_unhealthy);
  CHECK(defaults.healthy_z_range == mujoco::RangeKwarg{0.2, 1.0});
  CHECK(defaults.contact_force_range == mujoco::RangeKwarg{-1.0, 1.0});
  CHECK(defaults.reset_noise_scale == 0.1);
  CHECK(defaults.exclude_current_positions_from_observation);
  CHECK(defaults.xml_file.value.empty());
}

TEST_CASE("Ant-v4: tuple kwargs are YAML lists of two numbers, .inf included", "[mujoco]") {
  const EnvEntry* entry = builtin_registry().find_env("Ant-v4");
  REQUIRE(entry);
  const AnyConfig parsed =
      entry->parse(yaml("{healthy_z_range: [0.3, .inf], contact_force_range: [-.inf, 2]}"));
  const Ant::Config& c = parsed.get<Ant::Config>();
  CHECK(c.healthy_z_range == mujoco::RangeKwarg{0.3, kInf});
  CHECK(c.contact_force_range == mujoco::RangeKwarg{-kInf, 2.0});
  // The resolved config reads back as the same values.
  const YAML::Node resolved = parsed.resolved();
  CHECK(YAML::Dump(resolved["healthy_z_range"]) == "[0.3, .inf]");
  const Ant::Config again =
      entry->parse(ConfigNode::from_yaml(resolved, "resolved")).get<Ant::Config>();
  CHECK(again.healthy_z_range == c.healthy_z_range);
  CHECK(again.contact_force_range == c.contact_force_range);

  CHECK_THROWS_WITH(entry->parse(yaml("{healthy_z_range: [0.2]}")),
                    Catch::Contains("test.yaml:1:") && Catch::Contains("two numbers"));
  CHECK_THROWS_WITH(entry->parse(yaml("{healthy_z_range: 0.2}")), Catch::Contains("two numbers"));
  CHECK_THROWS_WITH(entry->parse(yaml("{healthy_z_range: [1.0, 0.2]}")),
                    Catch::Contains("low must not be above high"));
  CHECK_THROWS_WITH(entry->parse(yaml("{contact_force_range: [.nan, 1]}")), Catch::Contains("NaN"));
  CHECK_THROWS_WITH(entry->parse(yaml("{healthy_z_range: [a, 1]}")),
                    Catch::Contains("expected a number"));
}

TEST_CASE("Ant-v4: a step equals MuJoCo's C API stepped as Gymnasium does", "[mujoco]") {
  Ant::Config config;
  SECTION("defaults") { check_transitions(config, 1); }
  SECTION("contact forces observed and paid for (reward_ctrl is minus the contact cost)") {
    config.use_contact_forces = true;
    check_transitions(config, 2);
  }
  SECTION("positions observed, contact forces clipped to another range, weights changed") {
    config.exclude_current_positions_from_observation = false;
    config.use_contact_forces = true;
    config.contact_force_range = {-0.5, 3.0};
    config.contact_cost_weight = 0.01;
    config.ctrl_cost_weight = 0.25;
    config.healthy_reward = 2.0;
    check_transitions(config, 3);
  }
  SECTION("terminate_when_unhealthy false") {
    config.terminate_when_unhealthy = false;
    config.healthy_z_range = {0.3, 0.9};
    check_transitions(config, 4);
  }
}

TEST_CASE("Ant-v4: the healthy range includes its bounds", "[mujoco]") {
  // The torso's height after one step from the rest pose, found with the reference simulation.
  const std::vector<float> action(8, 0.5f);
  ReferenceSim sim("ant.xml");
  const std::vector<double> qpos = sim.qpos(), qvel(14, 0.0);
  sim.set_state(qpos, qvel);
  sim.step(action, 5);
  const double z = sim.data().qpos[2];
  const auto step_with = [&](double low, double high, bool terminate) {
    Ant::Config config;
    config.healthy_z_range = {low, high};
    config.terminate_when_unhealthy = terminate;
    Ant env(config);
    std::vector<float> obs(27);
    env.reset(0, obs);
    env.set_state(qpos, qvel);
    const StepResult r = env.step(action, obs);
    REQUIRE(env.qpos()[2] == z);
    return std::pair(r.terminated, env.info().get(env.info().find("reward_survive")));
  };
  CHECK(step_with(z, 1.0, true) == std::pair(false, 1.0));
  CHECK(step_with(0.2, z, true) == std::pair(false, 1.0));
  CHECK(step_with(std::nextafter(z, kInf), 1.0, true) == std::pair(true, 1.0));
  CHECK(step_with(0.2, std::nextafter(z, 0.0), true) == std::pair(true, 1.0));
  // Unhealthy without termination: the episode goes on and the healthy reward is not paid.
  CHECK(step_with(std::nextafter(z, kInf), 1.0, false) == std::pair(false, 0.0));
  CHECK(step_with(z, kInf, false) == std::pair(false, 1.0));

  // A non-finite velocity makes the state unhealthy whatever the height.
  Ant env;
  std::vector<float> obs(27);
  env.reset(0, obs);
  std::vector<double> bad_qvel(14, 0.0);
  env.set_state(qpos, bad_qvel);
  CHECK(env.is_healthy());
  bad_qvel[9] = std::numeric_limits<double>::infinity();
  env.set_state(qpos, bad_qvel);
  CHECK_FALSE(env.is_healthy());
}

TEST_CASE("Ant-v4: reset draws uniform qpos noise, then normal qvel noise", "[mujoco]") {
  Ant::Config config;
  config.reset_noise_scale = 0.2;
  Ant env(config);
  ReferenceSim sim("ant.xml");
  std::vector<float> obs(27);
  for (uint64_t seed : {5u, 6u}) {
    env.reset(seed, obs);
    // ant_v4.py's reset_model with this seed's stream: nq uniform draws, then nv normal ones,
    // given to set_state (whose mj_forward normalises the free joint's quaternion in qpos).
    Rng draws(seed);
    std::vector<double> qpos(env.init_qpos().begin(), env.init_qpos().end());
    std::vector<double> qvel(env.init_qvel().begin(), env.init_qvel().end());
    for (double& q : qpos) q += draws.uniform(-0.2, 0.2);
    for (double& v : qvel) v += 0.2 * draws.normal();
    sim.set_state(qpos, qvel);
    CHECK(std::vector<double>(env.qpos().begin(), env.qpos().end()) == sim.qpos());
    CHECK(std::vector<double>(env.qvel().begin(), env.qvel().end()) == sim.qvel());
    CHECK(obs[0] == static_cast<float>(sim.qpos()[2]));
  }
  CHECK(env.init_qpos()[2] == 0.75);  // the model's qpos0, not its custom init_qpos field
}

TEST_CASE("Ant-v4: a model of other sizes is refused", "[mujoco]") {
  Ant::Config config;
  config.xml_file.value = mujoco_model_file("half_cheetah.xml");
  CHECK_THROWS_WITH(Ant(config),
                    Catch::Contains("half_cheetah.xml") &&
                        Catch::Contains("this one has nq=9, nv=9, nu=6, nbody=8") &&
                        Catch::Contains("needs a model with nq=15, nv=14, nu=8, nbody=14"));
}

TEST_CASE("Ant-v4: a saved state resumes bit for bit", "[mujoco]") {
  Ant::Config config;
  config.use_contact_forces = true;
  config.terminate_when_unhealthy = false;
  Ant env(config), copy(config);
  std::vector<float> obs(111), obs_copy(111);
  env.reset(1, obs);
  copy.reset(2, obs_copy);
  Rng rng(5);
  for (int i = 0; i < 20; ++i) env.step(random_controls(rng, 8, 1.0), obs);
  TensorMap tensors;
  StateWriter writer(tensors, "env.");
  env.write_state(writer);
  copy.read_state(StateReader(tensors, "env."));
  for (int i = 0; i < 20; ++i) {
    const std::vector<float> action = random_controls(rng, 8, 1.0);
    const StepResult a = env.step(action, obs);
    const StepResult b = copy.step(action, obs_copy);
    CHECK(a.reward == b.reward);
    CHECK(obs == obs_copy);
    CHECK(env.info().values() == copy.info().values());
  }
}
