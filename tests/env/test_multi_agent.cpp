// The multi-agent shape of the env interface (include/rlrun/env.hpp): a VecEnv gives every
// agent of every env copy a column, steps them with step_agents, resets a copy when its agents'
// episode ends; TimeLimit truncates all agents, Monitor records their summed return; PPO trains
// one shared policy over all agents.
#include <catch2/catch.hpp>
#include <memory>

#include "fakes/agents_env.hpp"
#include "rlrun/algos/ppo/ppo.hpp"
#include "rlrun/env/vec_env.hpp"
#include "rlrun/wrappers/monitor.hpp"
#include "rlrun/wrappers/time_limit.hpp"

using namespace rlrun;
using rlrun::testing::AgentsEnv;

namespace {

// Two copies of a three-agent env, each under TimeLimit(4) and a Monitor.
VecEnv two_copies(int episode_length) {
  std::vector<EnvPtr> envs;
  for (int c = 0; c < 2; ++c) {
    EnvPtr env = std::make_unique<AgentsEnv>(3, episode_length);
    env = std::make_unique<TimeLimit>(std::move(env), 4);
    env = std::make_unique<Monitor>(std::move(env), "", 0.0, std::vector<std::string>{});
    envs.push_back(std::move(env));
  }
  return VecEnv(std::move(envs));
}

}  // namespace

TEST_CASE("multi-agent: one VecEnv column per agent, copies reset when their agents end",
          "[env][multi_agent]") {
  VecEnv env = two_copies(0);
  CHECK(env.num_envs() == 6);
  CHECK(env.num_copies() == 2);
  env.seed(5);
  const Eigen::MatrixXf first = env.reset();
  CHECK(first.rows() == 2);
  CHECK(first.cols() == 6);
  for (int i = 0; i < 6; ++i) CHECK(first.col(i).sum() == 1.0f);  // each agent's one-hot target
  for (int t = 1; t <= 4; ++t) {
    // Every agent acts its target: reward 1 each.
    Eigen::MatrixXf actions(1, 6);
    for (int i = 0; i < 6; ++i) actions(0, i) = env.obs()(1, i);
    env.step(actions);
    for (int i = 0; i < 6; ++i) {
      CHECK(env.rewards()[i] == 1.0);
      CHECK(env.truncated(i) == (t == 4));  // TimeLimit(4) truncates every agent
      CHECK_FALSE(env.terminated(i));
    }
  }
  // The Monitor of each copy counted one episode of 4 steps and 3 agents' rewards.
  const Info& info = env.info(0);
  const int r = info.find("episode.r"), l = info.find("episode.l");
  REQUIRE(r >= 0);
  CHECK(info.get(r) == 12.0);
  CHECK(info.get(l) == 4.0);
  CHECK(std::isfinite(env.final_obs()(0, 5)));  // the ended episode's last observations
}

TEST_CASE("multi-agent: other wrappers refuse several agents", "[env][multi_agent]") {
  struct Passthrough : Wrapper {
    using Wrapper::Wrapper;
  };
  Passthrough wrapped(std::make_unique<AgentsEnv>(2, 3));
  std::vector<float> obs(4), actions(2);
  std::vector<StepResult> results(2);
  wrapped.reset(0, obs);
  CHECK_THROWS_WITH(wrapped.step_agents(actions, obs, results),
                    Catch::Contains("does not support multi-agent envs"));
}

TEST_CASE("multi-agent: PPO trains one policy shared by all agents", "[env][multi_agent]") {
  VecEnv env = two_copies(0);
  env.seed(1);
  PPO::Config config;
  config.n_steps = 32;
  config.batch_size = 64;
  config.n_epochs = 4;
  config.learning_rate = Schedule::constant(3e-3);
  PPO ppo(config, AlgorithmSetup{env.observation_space(), env.action_space(), env.num_envs(), 1});
  TrainingHooks hooks;
  ppo.learn(env, 6 * 32 * 20, hooks);
  // The greedy shared policy now acts every agent's target.
  Eigen::MatrixXf actions;
  ppo.predict(env.obs(), true, actions);
  for (int i = 0; i < 6; ++i) CHECK(actions(0, i) == env.obs()(1, i));
}
