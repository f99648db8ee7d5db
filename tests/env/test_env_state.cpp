// Exact resume, env side: a VecEnv of registered envs (with TimeLimit and Monitor) saved
// mid-episode and restored into freshly built envs continues bit-identically.
#include <yaml-cpp/yaml.h>
#include <catch2/catch.hpp>

#include "rlrun/env/vec_env.hpp"
#include "rlrun/rng.hpp"
#include "rlrun/runtime/components/builtins.hpp"
#include "rlrun/runtime/experiment/env_factory.hpp"
#include "rlrun/runtime/experiment/experiment.hpp"

using namespace rlrun;

namespace {

VecEnv make_classic(const std::string& id, int n) {
  EnvSpec spec = default_env_spec(id, builtin_registry(), "test");
  return make_vec_env(spec, builtin_registry(), n, "");
}

// Random valid actions for every env, from a fixed stream.
Eigen::MatrixXf random_actions(const VecEnv& env, Rng& rng) {
  const Space& space = env.action_space();
  Eigen::MatrixXf actions(space.flat_dim(), env.num_envs());
  for (int i = 0; i < env.num_envs(); ++i)
    space.sample(rng, std::span<float>(actions.col(i).data(), actions.rows()));
  return actions;
}

struct Trace {
  std::vector<Eigen::MatrixXf> obs;
  std::vector<Eigen::VectorXd> rewards;
  std::vector<std::vector<int>> dones;
};

Trace run(VecEnv& env, Rng& action_rng, int steps) {
  Trace t;
  for (int s = 0; s < steps; ++s) {
    env.step(random_actions(env, action_rng));
    t.obs.push_back(env.obs());
    t.rewards.push_back(env.rewards());
    std::vector<int> d;
    for (int i = 0; i < env.num_envs(); ++i) d.push_back(env.terminated(i) * 2 + env.truncated(i));
    t.dones.push_back(d);
  }
  return t;
}

}  // namespace

TEST_CASE("A saved VecEnv of classic and probe envs resumes bit-identically", "[env][resume]") {
  for (const char* id :
       {"CartPole-v1", "Pendulum-v1", "MountainCar-v0", "MountainCarContinuous-v0", "Acrobot-v1",
        "IdentityEnv-v0", "IdentityEnvBox-v0", "IdentityEnvMultiDiscrete-v0",
        "IdentityEnvMultiBinary-v0", "DictReach-v0", "SimpleMultiObsEnv-v0"}) {
    INFO(id);
    VecEnv original = make_classic(id, 3);
    REQUIRE(original.can_save_state());
    original.seed(11);
    original.reset();
    Rng action_rng(5);
    // Past several episode ends (CartPole's random episodes last ~20 steps; the 200/500-step
    // time limits are crossed by Pendulum and MountainCar with 230 steps).
    run(original, action_rng, 230);
    TensorMap saved;
    StateWriter out(saved, "env/");
    original.write_state(out);
    const Rng action_rng_at_save = action_rng;
    const Trace expected = run(original, action_rng, 300);

    VecEnv restored = make_classic(id, 3);
    restored.read_state(StateReader(saved, "env/"));
    Rng replay_rng = action_rng_at_save;
    const Trace actual = run(restored, replay_rng, 300);
    for (size_t s = 0; s < expected.obs.size(); ++s) {
      INFO("step " << s);
      REQUIRE(actual.obs[s] == expected.obs[s]);
      REQUIRE(actual.rewards[s] == expected.rewards[s]);
      REQUIRE(actual.dones[s] == expected.dones[s]);
    }
  }
}

TEST_CASE("Restoring into another env or n_envs is refused with the key", "[env][resume]") {
  VecEnv cartpole = make_classic("CartPole-v1", 2);
  cartpole.seed(1);
  cartpole.reset();
  TensorMap saved;
  StateWriter out(saved);
  cartpole.write_state(out);
  VecEnv three = make_classic("CartPole-v1", 3);
  CHECK_THROWS_WITH(three.read_state(StateReader(saved)), Catch::Contains("'2/"));
  VecEnv pendulum = make_classic("Pendulum-v1", 2);
  CHECK_THROWS_AS(pendulum.read_state(StateReader(saved)), StateMismatch);
}

TEST_CASE("Restored step counters out of range are refused with the key", "[env][resume]") {
  // A checkpoint is untrusted: TimeLimit's elapsed steps must lie in [0, max_episode_steps],
  // the Monitor's counts must not be negative.
  VecEnv cartpole = make_classic("CartPole-v1", 1);
  cartpole.seed(1);
  cartpole.reset();
  TensorMap saved;
  StateWriter out(saved);
  cartpole.write_state(out);
  const auto with = [&](const std::string& suffix, int64_t value) {
    TensorMap changed = saved;
    int found = 0;
    for (auto& [key, tensor] : changed)
      if (key.size() >= suffix.size() &&
          key.compare(key.size() - suffix.size(), suffix.size(), suffix) == 0) {
        *tensor.data<int64_t>() = value;
        ++found;
      }
    REQUIRE(found == 1);
    return changed;
  };
  VecEnv restored = make_classic("CartPole-v1", 1);
  CHECK_NOTHROW(restored.read_state(StateReader(with("time_limit/elapsed_steps", 500))));
  CHECK_THROWS_WITH(restored.read_state(StateReader(with("time_limit/elapsed_steps", 501))),
                    Catch::Contains("time_limit/elapsed_steps' is 501, outside [0, 500]"));
  CHECK_THROWS_WITH(restored.read_state(StateReader(with("time_limit/elapsed_steps", -3))),
                    Catch::Contains("outside [0, 500]"));
  CHECK_THROWS_WITH(restored.read_state(StateReader(with("monitor/total_steps", -1))),
                    Catch::Contains("monitor/total_steps' is -1"));
  CHECK_THROWS_WITH(restored.read_state(StateReader(with("steps_beyond_terminated", -2))),
                    Catch::Contains("steps_beyond_terminated' is -2"));
}
