// MujocoEnv (Gymnasium's mujoco_env.py on MuJoCo's C API) and HalfCheetah-v4: the shipped models
// compile to Gymnasium's, transitions equal the tests' own MuJoCo stepping, state access, exact
// resume, bad model files, instability.
#include <catch2/catch.hpp>
#include <cmath>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "envs/mujoco/mujoco_reference.hpp"
#include "rlrun/core/errors.hpp"
#include "rlrun/env/physics_state.hpp"
#include "rlrun/envs/mujoco/half_cheetah.hpp"
#include "rlrun/rng.hpp"
#include "rlrun/runtime/components/builtins.hpp"
#include "rlrun/runtime/components/registry.hpp"
#include "rlrun/state.hpp"

using namespace rlrun;
using namespace rlrun::testing;
using rlrun::mujoco::HalfCheetah;

namespace {

std::vector<float> random_action(Rng& rng, int n, double bound = 1.0) {
  std::vector<float> a(static_cast<size_t>(n));
  for (float& v : a) v = static_cast<float>(rng.uniform(-bound, bound));
  return a;
}

}  // namespace

TEST_CASE("MuJoCo task models compile to Gymnasium's", "[mujoco]") {
  // tests/data/mujoco/gymnasium_model_hashes.txt: the hash of each Gymnasium 1.0.0 asset
  // compiled by this MuJoCo (scripts/data/make_mujoco_model_hashes.sh).
  std::ifstream in(std::string(test_paths::source_dir()) +
                   "/tests/data/mujoco/gymnasium_model_hashes.txt");
  REQUIRE(in);
  std::string line;
  int models = 0;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    std::istringstream fields(line);
    std::string file, hash;
    size_t bytes = 0;
    fields >> file >> hash >> bytes;
    ReferenceSim sim(file);
    char hex[17];
    std::snprintf(hex, sizeof hex, "%016llx",
                  static_cast<unsigned long long>(mujoco_model_hash(sim.model())));
    INFO(file);
    CHECK(std::string(hex) == hash);
    CHECK(static_cast<size_t>(mj_sizeModel(&sim.model())) == bytes);
    ++models;
  }
  CHECK(models >= 1);
}

TEST_CASE("HalfCheetah-v4: Gymnasium's spaces, kwargs and time limit", "[mujoco]") {
  HalfCheetah env;
  CHECK(env.id() == "HalfCheetah-v4");
  CHECK(env.observation_space().shape() == std::vector<int>{17});
  CHECK(env.action_space().shape() == std::vector<int>{6});
  CHECK(env.action_space().low() == std::vector<float>(6, -1.0f));
  CHECK(env.action_space().high() == std::vector<float>(6, 1.0f));
  CHECK(env.dt() == Approx(0.05));
  CHECK(env.frame_skip() == 5);
  HalfCheetah::Config with_x;
  with_x.exclude_current_positions_from_observation = false;
  CHECK(HalfCheetah(with_x).observation_space().shape() == std::vector<int>{18});
  const EnvEntry* entry = builtin_registry().find_env("HalfCheetah-v4");
  REQUIRE(entry);
  CHECK(entry->max_episode_steps == 1000);
  CHECK(entry->independent_copies);
}

TEST_CASE("HalfCheetah-v4: a step equals MuJoCo's C API stepped as Gymnasium does", "[mujoco]") {
  HalfCheetah env;
  ReferenceSim sim("half_cheetah.xml");
  std::vector<float> obs(17);
  env.reset(3, obs);
  Rng rng(11);
  for (int trial = 0; trial < 20; ++trial) {
    // A random state (as a user would set one with set_state) and a random action.
    std::vector<double> qpos(9), qvel(9);
    for (double& q : qpos) q = rng.uniform(-0.3, 0.3);
    for (double& v : qvel) v = rng.uniform(-2.0, 2.0);
    qpos[1] += 0.1;
    env.set_state(qpos, qvel);
    sim.set_state(qpos, qvel);
    const std::vector<float> action = random_action(rng, 6, 1.2);  // beyond ctrlrange too

    const double x_before = sim.data().qpos[0];
    sim.step(action, 5);
    const StepResult r = env.step(action, obs);

    const double x_velocity = (sim.data().qpos[0] - x_before) / (0.01 * 5);
    float squares = 0.0f;  // np.sum(np.square(action)) in float32 (fewer than 8 values)
    for (float a : action) squares += a * a;
    const double ctrl_cost = 0.1 * static_cast<double>(squares);
    CHECK(r.reward == x_velocity - ctrl_cost);
    CHECK_FALSE(r.terminated);
    CHECK_FALSE(r.truncated);
    for (int i = 0; i < 8; ++i) CHECK(obs[i] == static_cast<float>(sim.data().qpos[i + 1]));
    for (int i = 0; i < 9; ++i) CHECK(obs[8 + i] == static_cast<float>(sim.data().qvel[i]));
    CHECK(env.qpos()[0] == sim.data().qpos[0]);
    const Info& info = env.info();
    CHECK(info.get(info.find("x_position")) == sim.data().qpos[0]);
    CHECK(info.get(info.find("x_velocity")) == x_velocity);
    CHECK(info.get(info.find("reward_run")) == x_velocity);
    CHECK(info.get(info.find("reward_ctrl")) == -ctrl_cost);
  }
}

TEST_CASE("HalfCheetah-v4: reset adds Gymnasium's noise to the rest pose and seeds repeat",
          "[mujoco]") {
  HalfCheetah env;
  std::vector<float> a(17), b(17);
  env.reset(7, a);
  const std::vector<double> first(env.qpos().begin(), env.qpos().end());
  env.reset(7, b);
  CHECK(a == b);
  for (size_t i = 0; i < first.size(); ++i) {
    CHECK(std::abs(first[i] - env.init_qpos()[i]) <= 0.1);
    CHECK(env.qpos()[i] == first[i]);
  }
  env.reset(8, b);
  CHECK(a != b);
  CHECK(env.init_qpos()[0] == 0.0);  // the model's qpos0: the torso's joints at rest
}

TEST_CASE("HalfCheetah-v4: a saved state resumes bit for bit", "[mujoco]") {
  HalfCheetah env, copy;
  std::vector<float> obs(17), obs_copy(17);
  env.reset(1, obs);
  copy.reset(2, obs_copy);
  Rng rng(5);
  for (int i = 0; i < 30; ++i) env.step(random_action(rng, 6), obs);
  TensorMap tensors;
  StateWriter writer(tensors, "env.");
  env.write_state(writer);
  copy.read_state(StateReader(tensors, "env."));
  for (int i = 0; i < 30; ++i) {
    const std::vector<float> action = random_action(rng, 6);
    const StepResult a = env.step(action, obs);
    const StepResult b = copy.step(action, obs_copy);
    CHECK(a.reward == b.reward);
    CHECK(obs == obs_copy);
  }
}

TEST_CASE("MuJoCo envs: a missing or broken model file is a clear error", "[mujoco]") {
  HalfCheetah::Config config;
  config.xml_file.value = "/nonexistent/cheetah.xml";
  CHECK_THROWS_WITH(HalfCheetah(config),
                    Catch::Contains("/nonexistent/cheetah.xml") && Catch::Contains("no such"));
  const std::string broken = "/tmp/rlrun_broken_cheetah.xml";
  std::ofstream(broken)
      << "<mujoco>\n  <worldbody>\n    <geom type=\"sphere\"/>\n"
         "    <body><joint type=\"nonsense\"/></body>\n  </worldbody>\n</mujoco>\n";
  config.xml_file.value = broken;
  CHECK_THROWS_WITH(HalfCheetah(config), Catch::Contains(broken) && Catch::Contains("line 4"));
}

TEST_CASE("MuJoCo envs: an unstable simulation ends the episode", "[mujoco]") {
  HalfCheetah env;
  std::vector<float> obs(17);
  env.reset(0, obs);
  std::vector<double> qpos(env.init_qpos().begin(), env.init_qpos().end());
  std::vector<double> qvel(9, 0.0);
  qvel[3] = 1e30;  // MuJoCo's "huge value" check resets the simulation
  env.set_state(qpos, qvel);
  const StepResult r = env.step(std::vector<float>(6, 0.0f), obs);
  CHECK(r.truncated);
  CHECK_FALSE(r.terminated);
  for (float v : obs) CHECK(std::isfinite(v));
}

TEST_CASE("MuJoCo envs: xml_file names a shipped model by its file name, as Gymnasium's assets",
          "[mujoco]") {
  // Gymnasium's expand_model_path: a bare name is looked up among its assets.
  HalfCheetah::Config config;
  config.xml_file.value = "half_cheetah.xml";
  CHECK(HalfCheetah(config).observation_space().shape() == std::vector<int>{17});
  config.xml_file.value = "no_such_model.xml";
  CHECK_THROWS_WITH(HalfCheetah(config), Catch::Contains("no_such_model.xml"));
}
