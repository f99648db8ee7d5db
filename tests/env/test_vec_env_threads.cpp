// VecEnv stepping independent env copies on a thread pool (vec_env.hpp, EnvPool's way): the
// batch must be the same bits as stepping one copy after another, for every pool size, through
// auto-resets and time limits; copies not vouched for never go to the pool. (Whether a real
// run's steps are worth the hand-off is measured at run time; no test asserts a timing.)
#include <catch2/catch.hpp>

#include <algorithm>
#include <memory>
#include <vector>

#include "env/vec_env_trace.hpp"
#include "rlrun/core/thread_pool.hpp"
#include "rlrun/env/vec_env.hpp"
#include "rlrun/envs/classic/cartpole.hpp"
#include "rlrun/envs/lunar_lander/lunar_lander.hpp"
#include "rlrun/envs/mujoco/half_cheetah.hpp"
#include "rlrun/runtime/components/builtins.hpp"
#include "rlrun/runtime/experiment/env_factory.hpp"
#include "rlrun/runtime/experiment/experiment.hpp"
#include "rlrun/wrappers/time_limit.hpp"

using namespace rlrun;
using rlrun::testing::trace_random_steps;
using rlrun::testing::VecEnvTrace;

namespace {

template <class E>
VecEnv copies(int n, int max_steps) {
  std::vector<EnvPtr> envs;
  for (int i = 0; i < n; ++i)
    envs.push_back(std::make_unique<TimeLimit>(std::make_unique<E>(), max_steps));
  return VecEnv(std::move(envs));
}

// `make_copies()` builds the same VecEnv each call; stepped on pools of 1 to 8 threads it must
// go parallel (on more than one) and give the bits of stepping one copy after another.
template <class MakeCopies>
void check_pooled_equals_serial(const MakeCopies& make_copies, int steps) {
  VecEnv serial = make_copies();
  const VecEnvTrace want = trace_random_steps(serial, steps, 11);
  REQUIRE_FALSE(serial.steps_in_parallel());
  CHECK(std::count(want.dones.begin(), want.dones.end(), 1) > 0);  // auto-resets happened
  for (const int threads : {1, 2, 3, 8}) {
    INFO(threads << " threads");
    ThreadPool pool(threads);
    VecEnv pooled = make_copies();
    pooled.set_thread_pool(&pool);
    pooled.set_parallel_step_seconds(0.0);
    const VecEnvTrace got = trace_random_steps(pooled, steps, 11);
    CHECK(pooled.steps_in_parallel() == (threads > 1));
    CHECK(got.obs == want.obs);
    CHECK(got.final_obs == want.final_obs);
    CHECK(got.rewards == want.rewards);
    CHECK(got.dones == want.dones);
  }
}

template <class E>
void check_pooled_equals_serial(int n, int max_steps, int steps) {
  check_pooled_equals_serial(
      [&] {
        VecEnv env = copies<E>(n, max_steps);
        env.set_independent_copies(true);
        return env;
      },
      steps);
}

}  // namespace

TEST_CASE("VecEnv on a pool: independent copies step at once, with the serial bits",
          "[vec_env][thread_pool]") {
  SECTION("CartPole") { check_pooled_equals_serial<CartPole>(5, 50, 400); }
  SECTION("LunarLander (a Box2D world per copy)") {
    check_pooled_equals_serial<LunarLander>(4, 60, 300);
  }
  SECTION("HalfCheetah (an mjData per copy, one model file each)") {
    check_pooled_equals_serial<mujoco::HalfCheetah>(4, 40, 120);
  }
}

TEST_CASE("VecEnv on a pool: copies nobody vouched for stay on one thread",
          "[vec_env][thread_pool]") {
  ThreadPool pool(3);
  VecEnv unvouched = copies<CartPole>(4, 50);
  unvouched.set_thread_pool(&pool);
  unvouched.set_parallel_step_seconds(0.0);
  trace_random_steps(unvouched, 40, 11);
  CHECK_FALSE(unvouched.steps_in_parallel());
}

TEST_CASE("VecEnv on a pool: env.normalize's batched statistics keep copies independent",
          "[vec_env][thread_pool]") {
  // SB3's VecNormalize sits above the VecEnv: the copies step, then the batch updates the
  // statistics. rlrun's step hook does that on the calling thread, so the copies may step at
  // once (before, any statistics wrapper kept a run with env.normalize on one thread).
  EnvSpec spec = default_env_spec("CartPole-v1", builtin_registry(), "test");
  spec.section.normalize.enabled = true;  // observations and rewards, VecNormalize's defaults
  check_pooled_equals_serial([&] { return make_vec_env(spec, builtin_registry(), 4, ""); }, 300);
  SECTION("a per-copy NormalizeObservation of env.wrappers shares statistics while stepping") {
    const Experiment e =
        parse_experiment(ConfigNode::load_string("run: {name: t}\nenv: {id: CartPole-v1, wrappers: "
                                                 "[{id: NormalizeObservation}]}\nalgo: {id: PPO}\n",
                                                 "wrapped.yaml"),
                         builtin_registry());
    const EnvSpec& wrapped = e.env;
    ThreadPool pool(2);
    VecEnv pooled = make_vec_env(wrapped, builtin_registry(), 4, "");
    pooled.set_thread_pool(&pool);
    pooled.set_parallel_step_seconds(0.0);
    trace_random_steps(pooled, 20, 5);
    CHECK_FALSE(pooled.steps_in_parallel());
  }
}
