// Exact resume, algorithm side (issue 4): stopping at a safe point, saving the model, the
// training state and the envs, and continuing in a fresh process-like copy (new algorithm,
// new envs, state loaded) ends with the same bits as the uninterrupted run.
#include <yaml-cpp/yaml.h>
#include <catch2/catch.hpp>

#include "rlrun/algos/a2c/a2c.hpp"
#include "rlrun/algos/ddpg/ddpg.hpp"
#include "rlrun/algos/ppo/ppo.hpp"
#include "rlrun/algos/sac/sac.hpp"
#include "rlrun/algos/tqc/tqc.hpp"
#include "rlrun/env/vec_env.hpp"
#include "rlrun/runtime/components/builtins.hpp"
#include "rlrun/runtime/experiment/env_factory.hpp"
#include "rlrun/runtime/experiment/experiment.hpp"

using namespace rlrun;

namespace {

VecEnv make_envs(const std::string& id, int n, uint64_t seed) {
  EnvSpec spec = default_env_spec(id, builtin_registry(), "test");
  VecEnv env = make_vec_env(spec, builtin_registry(), n, "");
  env.seed(seed);
  return env;
}

// Every float32 tensor of a model, concatenated in name order.
Eigen::VectorXf flatten(const TensorMap& model) {
  Eigen::VectorXf all;
  for (const auto& [name, tensor] : model) {
    const Eigen::Index n = tensor.numel();
    all.conservativeResize(all.size() + n);
    all.tail(n) = Eigen::Map<const Eigen::VectorXf>(tensor.data<float>(), n);
  }
  return all;
}

struct Snapshot {
  TensorMap model, state;
};

// Trains `algo` to `total` steps; at the first safe point at or after `save_at` steps, saves
// everything into `snapshot`.
template <class Algo>
Eigen::VectorXf train_and_snapshot(Algo& algo, VecEnv& env, int64_t total, int64_t save_at,
                                   Snapshot& snapshot, int64_t& saved_at) {
  TrainingHooks hooks;
  saved_at = -1;
  hooks.at_safe_point = [&](int64_t steps) {
    if (saved_at < 0 && steps >= save_at) {
      saved_at = steps;
      algo.save(snapshot.model);
      StateWriter algo_out(snapshot.state, "algo/");
      algo.save_training_state(algo_out);
      StateWriter env_out(snapshot.state, "env/");
      env.write_state(env_out);
    }
    return true;
  };
  algo.learn(env, total, hooks);
  TensorMap final_model;
  algo.save(final_model);
  return flatten(final_model);
}

template <class Algo>
Eigen::VectorXf resume(Algo& algo, VecEnv& env, int64_t total, const Snapshot& snapshot) {
  algo.load(snapshot.model);
  algo.load_training_state(StateReader(snapshot.state, "algo/"));
  env.read_state(StateReader(snapshot.state, "env/"));
  TrainingHooks hooks;
  algo.learn(env, total, hooks);
  TensorMap final_model;
  algo.save(final_model);
  return flatten(final_model);
}

// Trains `cfg` on `n_envs` copies of `env_id` (seeded `seed`) to `total` steps twice:
// uninterrupted, and stopped at the first safe point at or after `save_at` steps, saved, and
// continued to `total` by a fresh copy built with another seed (so everything must come from
// the checkpoint). Both must end with the same weights. Returns the step of the snapshot.
template <class Algo>
int64_t check_exact_resume(const typename Algo::Config& cfg, const std::string& env_id, int n_envs,
                           uint64_t seed, int64_t total, int64_t save_at) {
  Snapshot snapshot;
  int64_t saved_at = 0;
  VecEnv env1 = make_envs(env_id, n_envs, seed);
  Algo uninterrupted(cfg,
                     AlgorithmSetup{env1.observation_space(), env1.action_space(), n_envs, seed});
  const Eigen::VectorXf expected =
      train_and_snapshot(uninterrupted, env1, total, save_at, snapshot, saved_at);
  VecEnv env2 = make_envs(env_id, n_envs, seed);
  Algo resumed(cfg,
               AlgorithmSetup{env2.observation_space(), env2.action_space(), n_envs, seed + 1000});
  const Eigen::VectorXf actual = resume(resumed, env2, total, snapshot);
  CHECK(resumed.num_timesteps() == total);
  REQUIRE(actual.size() == expected.size());
  CHECK(actual == expected);
  return saved_at;
}

}  // namespace

TEST_CASE("PPO resumed from a safe point ends with the uninterrupted run's weights",
          "[algos][resume]") {
  const std::string id = GENERATE(as<std::string>{}, "CartPole-v1", "Pendulum-v1");
  INFO(id);
  PPO::Config cfg;
  cfg.n_steps = 64;
  cfg.batch_size = 32;
  cfg.n_epochs = 3;
  cfg.learning_rate = Schedule::linear(1e-3);
  // 4 iterations of 2 x 64 steps: the first safe point >= 900.
  CHECK(check_exact_resume<PPO>(cfg, id, 2, 7, 2048, 900) == 1024);
}

TEST_CASE(
    "A2C (RMSprop and Adam) resumed from a safe point ends with the uninterrupted run's "
    "weights",
    "[algos][resume]") {
  A2C::Config cfg;
  cfg.use_rms_prop = GENERATE(true, false);
  INFO("use_rms_prop " << cfg.use_rms_prop);
  CHECK(check_exact_resume<A2C>(cfg, "CartPole-v1", 4, 3, 1000, 500) == 500);
}

TEST_CASE("DDPG resumed from a safe point ends with the uninterrupted run's weights",
          "[algos][resume][ddpg]") {
  // DDPG forwards its training state to the TD3 it is built on.
  DDPG::Config cfg;
  cfg.off_policy.learning_starts = 100;
  cfg.off_policy.batch_size = 32;
  cfg.policy.net_arch = {{16, 16}, {16, 16}};
  cfg.action_noise.noise_type = "ornstein-uhlenbeck";
  CHECK(check_exact_resume<DDPG>(cfg, "Pendulum-v1", 1, 3, 600, 300) == 300);
}

TEST_CASE("PPO and A2C with gSDE resume from a safe point to the uninterrupted run's weights",
          "[algos][resume][gsde]") {
  // sde_sample_freq 3 does not divide n_steps: matrices drawn mid-rollout are in use at no safe
  // point, but the checkpoint holds them and the action stream that draws them.
  PPO::Config ppo;
  ppo.n_steps = 32;
  ppo.batch_size = 16;
  ppo.n_epochs = 2;
  ppo.use_sde = true;
  ppo.sde_sample_freq = 3;
  ppo.policy.full_std = false;
  CHECK(check_exact_resume<PPO>(ppo, "Pendulum-v1", 2, 4, 640, 300) == 320);
  A2C::Config a2c;
  a2c.use_sde = true;
  a2c.sde_sample_freq = 2;
  CHECK(check_exact_resume<A2C>(a2c, "Pendulum-v1", 2, 6, 400, 200) == 200);
}

TEST_CASE(
    "SAC and TQC (plain and gSDE) resume from a safe point to the uninterrupted run's "
    "weights",
    "[algos][resume][gsde][tqc]") {
  const bool use_sde = GENERATE(false, true);
  INFO("use_sde " << use_sde);
  const auto small = [&](auto cfg) {
    cfg.off_policy.learning_starts = 64;
    cfg.off_policy.batch_size = 32;
    cfg.off_policy.train_freq.frequency = 8;
    cfg.off_policy.gradient_steps = 4;
    cfg.policy.net_arch = {{16, 16}, {16, 16}};
    cfg.use_sde = use_sde;
    cfg.sde_sample_freq = 3;
    return cfg;
  };
  CHECK(check_exact_resume<SAC>(small(SAC::Config()), "Pendulum-v1", 2, 3, 400, 200) == 208);
  TQC::Config tqc = small(TQC::Config());
  tqc.policy.n_quantiles = 7;
  tqc.top_quantiles_to_drop_per_net = 3;
  CHECK(check_exact_resume<TQC>(tqc, "Pendulum-v1", 2, 3, 400, 200) == 208);
}
