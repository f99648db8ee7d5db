// VecEnv: SB3 DummyVecEnv semantics (seed + i, same-step auto-reset with the final
// observation kept, the step's info kept, rewards per env).
#include <catch2/catch.hpp>
#include <cmath>
#include <memory>
#include <stdexcept>
#include <vector>

#include "fakes/counter_env.hpp"
#include "rlrun/env/vec_env.hpp"
#include "rlrun/envs/classic/cartpole.hpp"
#include "rlrun/envs/classic/pendulum.hpp"
#include "rlrun/wrappers/time_limit.hpp"

using namespace rlrun;
using rlrun::testing::CounterEnv;

namespace {

std::vector<EnvPtr> cartpoles(int n, int max_steps = CartPole::kMaxEpisodeSteps) {
  std::vector<EnvPtr> envs;
  for (int i = 0; i < n; ++i)
    envs.push_back(std::make_unique<TimeLimit>(std::make_unique<CartPole>(), max_steps));
  return envs;
}

std::vector<EnvPtr> counters(std::vector<int> lengths) {
  std::vector<EnvPtr> envs;
  for (int length : lengths) envs.push_back(std::make_unique<CounterEnv>(length));
  return envs;
}

std::vector<float> column(const Eigen::MatrixXf& m, int i) {
  return std::vector<float>(m.col(i).data(), m.col(i).data() + m.rows());
}

}  // namespace

TEST_CASE("VecEnv seeds env i with seed + i on the next reset only", "[vec_env]") {
  VecEnv vec(cartpoles(3));
  CHECK(vec.num_envs() == 3);
  CHECK(vec.observation_space().flat_dim() == 4);
  CHECK(vec.action_space().describe() == "Discrete(2)");

  vec.seed(10);
  const Eigen::MatrixXf first = vec.reset();
  REQUIRE(first.rows() == 4);
  REQUIRE(first.cols() == 3);
  const Eigen::MatrixXf second = vec.reset();  // no seed: each env continues its stream
  for (int i = 0; i < 3; ++i) {
    CartPole alone;
    std::vector<float> a(4), b(4);
    alone.reset(10 + i, a);
    alone.reset(std::nullopt, b);
    CHECK(column(first, i) == a);
    CHECK(column(second, i) == b);
  }
  CHECK(column(first, 0) != column(first, 1));
}

TEST_CASE("VecEnv auto-resets finished envs in the same step", "[vec_env]") {
  // Env 0 ends every 2 steps, env 1 every 3.
  VecEnv vec(counters({2, 3}));
  vec.seed(0);  // starts 0 and 1
  vec.reset();
  Eigen::MatrixXf actions(1, 2);
  actions << 0.5f, -2.0f;

  vec.step(actions);
  CHECK(vec.obs()(0, 0) == 1.0f);
  CHECK(vec.obs()(0, 1) == 2.0f);
  CHECK_FALSE(vec.done(0));
  CHECK_FALSE(vec.done(1));
  CHECK(std::isnan(vec.final_obs()(0, 0)));
  CHECK(vec.rewards()(0) == 0.5);
  CHECK(vec.rewards()(1) == -2.0);
  CHECK(vec.info(0).get(vec.info(0).find("is_success")) == 0.0);

  vec.step(actions);  // env 0 terminates: final obs 2, auto-reset (no seed) to 0 + 100
  CHECK(vec.terminated(0));
  CHECK_FALSE(vec.truncated(0));
  CHECK(vec.done(0));
  CHECK(vec.final_obs()(0, 0) == 2.0f);
  CHECK(vec.obs()(0, 0) == 100.0f);
  // The info is the terminating step's (is_success = 1), not the reset's (absent).
  const int key = vec.info(0).find("is_success");
  REQUIRE(key >= 0);
  CHECK(vec.info(0).get(key) == 1.0);
  CHECK_FALSE(vec.done(1));
  CHECK(std::isnan(vec.final_obs()(0, 1)));
  CHECK(vec.obs()(0, 1) == 3.0f);

  vec.step(actions);  // env 1 terminates now
  CHECK_FALSE(vec.done(0));
  CHECK(vec.obs()(0, 0) == 101.0f);
  CHECK(vec.done(1));
  CHECK(vec.final_obs()(0, 1) == 4.0f);
  CHECK(vec.obs()(0, 1) == 101.0f);
  CHECK(dynamic_cast<CounterEnv&>(vec.env(0)).resets() == 2);
  CHECK(dynamic_cast<CounterEnv&>(vec.env(1)).resets() == 2);
}

TEST_CASE("VecEnv final_obs is the terminal observation of a real env", "[vec_env]") {
  // TimeLimit of 3 steps: compare with a standalone twin fed the same actions.
  VecEnv vec(cartpoles(2, 3));
  vec.seed(5);
  vec.reset();
  TimeLimit twin(std::make_unique<CartPole>(), 3);
  std::vector<float> twin_obs(4);
  twin.reset(5 + 1, twin_obs);
  Eigen::MatrixXf actions(1, 2);
  actions << 1.0f, 0.0f;
  for (int t = 1; t <= 3; ++t) {
    vec.step(actions);
    const StepResult r = twin.step(std::vector<float>{0.0f}, twin_obs);
    CHECK(vec.truncated(1) == r.truncated);
    CHECK(vec.rewards()(1) == r.reward);
    if (t < 3) CHECK(column(vec.obs(), 1) == twin_obs);
  }
  REQUIRE(vec.done(1));
  CHECK(column(vec.final_obs(), 1) == twin_obs);
  twin.reset(std::nullopt, twin_obs);
  CHECK(column(vec.obs(), 1) == twin_obs);
}

TEST_CASE("VecEnv rejects mismatched spaces and action shapes", "[vec_env]") {
  std::vector<EnvPtr> mixed;
  mixed.push_back(std::make_unique<CartPole>());
  mixed.push_back(std::make_unique<Pendulum>());
  CHECK_THROWS_AS(VecEnv(std::move(mixed)), std::invalid_argument);
  CHECK_THROWS_AS(VecEnv(std::vector<EnvPtr>{}), std::invalid_argument);

  VecEnv vec(cartpoles(2));
  vec.reset();
  CHECK_THROWS_AS(vec.step(Eigen::MatrixXf::Zero(1, 3)), std::invalid_argument);
  CHECK_THROWS_AS(vec.step(Eigen::MatrixXf::Zero(2, 2)), std::invalid_argument);
}
