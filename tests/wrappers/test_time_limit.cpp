// TimeLimit (gymnasium/wrappers/common.py): truncation exactly at max_episode_steps, counter
// reset by reset(), terminated passed through.
#include <catch2/catch.hpp>
#include <memory>
#include <stdexcept>
#include <vector>

#include "rlrun/envs/classic/cartpole.hpp"
#include "rlrun/envs/classic/pendulum.hpp"
#include "rlrun/wrappers/time_limit.hpp"

using namespace rlrun;

TEST_CASE("TimeLimit truncates exactly at max_episode_steps", "[wrappers]") {
  TimeLimit env(std::make_unique<Pendulum>(), 5);
  CHECK(env.max_episode_steps() == 5);
  std::vector<float> obs(3);
  const std::vector<float> action{0.0f};
  for (int episode = 0; episode < 2; ++episode) {
    env.reset(episode == 0 ? std::optional<uint64_t>(3) : std::nullopt, obs);
    CHECK(env.elapsed_steps() == 0);
    for (int t = 1; t <= 5; ++t) {
      const StepResult r = env.step(action, obs);
      INFO("episode " << episode << " step " << t);
      CHECK(r.truncated == (t == 5));
      CHECK_FALSE(r.terminated);
      CHECK(env.elapsed_steps() == t);
    }
  }
  // Stepping on past the limit keeps reporting truncation, as Gymnasium does (elapsed >= max).
  CHECK(env.step(action, obs).truncated);
}

TEST_CASE("TimeLimit passes terminated through, both flags can be set", "[wrappers]") {
  TimeLimit env(std::make_unique<CartPole>(), 1);
  std::vector<float> obs(4);
  env.reset(0, obs);
  dynamic_cast<CartPole&>(env.unwrapped()).set_state(std::vector<double>{2.39, 1.0, 0, 0}, obs);
  const StepResult r = env.step(std::vector<float>{1.0f}, obs);
  CHECK(r.terminated);
  CHECK(r.truncated);

  TimeLimit long_limit(std::make_unique<CartPole>(), 100);
  long_limit.reset(0, obs);
  dynamic_cast<CartPole&>(long_limit.unwrapped())
      .set_state(std::vector<double>{2.39, 1.0, 0, 0}, obs);
  const StepResult r2 = long_limit.step(std::vector<float>{1.0f}, obs);
  CHECK(r2.terminated);
  CHECK_FALSE(r2.truncated);
}

TEST_CASE("TimeLimit forwards the wrapped env and validates its arguments", "[wrappers]") {
  TimeLimit env(std::make_unique<CartPole>(), CartPole::kMaxEpisodeSteps);
  CHECK(env.id() == "CartPole-v1");
  CHECK(env.action_space().describe() == "Discrete(2)");
  CHECK(env.observation_space().flat_dim() == 4);
  CHECK(dynamic_cast<CartPole*>(&env.unwrapped()) != nullptr);
  CHECK_THROWS_AS(TimeLimit(std::make_unique<CartPole>(), 0), std::invalid_argument);
  CHECK_THROWS_AS(TimeLimit(nullptr, 10), std::invalid_argument);
}
