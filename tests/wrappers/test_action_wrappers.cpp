#include <catch2/catch.hpp>

#include "rlrun/envs/classic/cartpole.hpp"
#include "rlrun/envs/classic/pendulum.hpp"
#include "rlrun/wrappers/box_as_discrete.hpp"
#include "rlrun/wrappers/discrete_as_box.hpp"

using namespace rlrun;

TEST_CASE("DiscreteAsBox: argmax of the scores picks the discrete action", "[wrappers]") {
  DiscreteAsBox env(std::make_unique<CartPole>());
  CHECK(env.action_space().describe() == "Box(-1.0, 1.0, (2,), float32)");
  // Same start, opposite pushes: the cart velocity has opposite signs.
  std::vector<float> obs(4), left{0.9f, -0.3f}, right{-0.5f, 0.2f};
  env.reset(5, obs);
  env.step(left, obs);
  CHECK(obs[1] < 0.0f);
  env.reset(5, obs);
  env.step(right, obs);
  CHECK(obs[1] > 0.0f);
  CHECK_THROWS_AS(DiscreteAsBox(std::make_unique<Pendulum>()), std::invalid_argument);
}

TEST_CASE("BoxAsDiscrete: a grid over the bounds, first dimension fastest", "[wrappers]") {
  BoxAsDiscrete::Config config;
  config.bins = 5;
  BoxAsDiscrete env(std::make_unique<Pendulum>(), config);
  CHECK(env.action_space().describe() == "Discrete(5)");
  // Torques -2, -1, 0, 1, 2: from the same state, a larger torque gives a larger speed.
  std::vector<float> obs(3);
  float previous_speed = -1e9f;
  for (int a = 0; a < 5; ++a) {
    env.reset(11, obs);
    const float action = static_cast<float>(a);
    env.step({&action, 1}, obs);
    CHECK(obs[2] > previous_speed);
    previous_speed = obs[2];
  }
  const float outside = 5.0f;
  CHECK_THROWS(env.step({&outside, 1}, obs));
  CHECK_THROWS_AS(BoxAsDiscrete(std::make_unique<CartPole>()), std::invalid_argument);
}
