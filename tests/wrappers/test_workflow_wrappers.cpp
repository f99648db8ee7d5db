// ClipAction, RescaleAction, FrameStack, TransformReward, RewardShaping: hand-computed values,
// and their strict YAML parsing through the registry (as `env.wrappers` entries are built).
#include <catch2/catch.hpp>

#include "rlrun/core/errors.hpp"
#include "rlrun/runtime/components/builtins.hpp"
#include "rlrun/wrappers/clip_action.hpp"
#include "rlrun/wrappers/frame_stack.hpp"
#include "rlrun/wrappers/rescale_action.hpp"
#include "rlrun/wrappers/reward_shaping.hpp"
#include "rlrun/wrappers/transform_reward.hpp"
#include "wrappers/scripted_env.hpp"

using namespace rlrun;
using rlrun::testing::ScriptedEnv;

namespace {

// Observations (x, y) per step as given, reward 1 every step, episodes of `length` steps.
std::unique_ptr<ScriptedEnv> script(std::vector<std::vector<float>> steps, int length = 100,
                                    int act_dim = 1) {
  return std::make_unique<ScriptedEnv>(std::vector<std::vector<float>>{{1.0f, -2.0f}},
                                       std::move(steps), std::vector<double>{1.0}, length, act_dim);
}

// Builds a wrapper from YAML text the way make_env does.
EnvPtr from_yaml(const std::string& yaml, EnvPtr inner) {
  const ConfigNode node = ConfigNode::load_string(yaml, "test.yaml");
  const WrapperEntry& entry =
      builtin_registry().wrapper(node.child("id").as_string(), node.child("id"));
  return entry.make(std::move(inner), entry.parse(node));
}

}  // namespace

TEST_CASE("ClipAction: clips to the inner bounds, exposes an unbounded Box", "[wrappers]") {
  auto inner = script({{0.0f, 0.0f}}, 100, 2);
  ScriptedEnv* raw = inner.get();
  ClipAction env(std::move(inner));
  CHECK(env.action_space().describe() == "Box(-inf, inf, (2,), float32)");
  std::vector<float> obs(2), action{5.0f, -0.5f};
  env.reset(std::nullopt, obs);
  env.step(action, obs);
  CHECK(raw->last_action() == std::vector<float>{2.0f, -0.5f});
  action = {-7.0f, 1.5f};
  env.step(action, obs);
  CHECK(raw->last_action() == std::vector<float>{-2.0f, 1.5f});
}

TEST_CASE("RescaleAction: [min_action, max_action] maps affinely onto the env's bounds",
          "[wrappers]") {
  auto inner = script({{0.0f, 0.0f}}, 100, 2);
  ScriptedEnv* raw = inner.get();
  RescaleAction::Config config;
  config.min_action.values = {0.0};
  config.max_action.values = {1.0, 4.0};  // per dimension
  RescaleAction env(std::move(inner), config);
  CHECK(env.action_space().low() == std::vector<float>{0.0f, 0.0f});
  CHECK(env.action_space().high() == std::vector<float>{1.0f, 4.0f});
  std::vector<float> obs(2), action{0.25f, 1.0f};
  env.reset(std::nullopt, obs);
  env.step(action, obs);
  // inner low -2, high 2: -2 + 4 * 0.25 = -1; -2 + 4 * (1 / 4) = -1.
  CHECK(raw->last_action() == std::vector<float>{-1.0f, -1.0f});
  action = {1.0f, 6.0f};  // the upper bound, and beyond it (clipped to the env's bound)
  env.step(action, obs);
  CHECK(raw->last_action() == std::vector<float>{2.0f, 2.0f});

  CHECK_THROWS_AS(
      from_yaml("{id: RescaleAction, min_action: [0, 0, 0]}", script({{0.0f, 0.0f}}, 100, 2)),
      std::invalid_argument);
  CHECK_THROWS_AS(
      from_yaml("{id: RescaleAction, min_action: 1, max_action: 1}", script({{0.0f, 0.0f}})),
      std::invalid_argument);
  // YAML scalars and lists both parse.
  EnvPtr scalar =
      from_yaml("{id: RescaleAction, min_action: -3, max_action: 3}", script({{0.0f, 0.0f}}));
  CHECK(scalar->action_space().describe() == "Box(-3.0, 3.0, (1,), float32)");
}

TEST_CASE("FrameStack: oldest first, zero or reset padding, a fresh stack after reset",
          "[wrappers]") {
  FrameStack::Config config;
  config.n_stack = 3;
  FrameStack env(script({{1.5f, 0.5f}, {3.0f, -1.0f}}), config);
  CHECK(env.observation_space().describe() == "Box(-100.0, 100.0, (3, 2), float32)");
  std::vector<float> obs(6), action{0.0f};
  env.reset(std::nullopt, obs);
  CHECK(obs == std::vector<float>{0, 0, 0, 0, 1.0f, -2.0f});
  env.step(action, obs);
  CHECK(obs == std::vector<float>{0, 0, 1.0f, -2.0f, 1.5f, 0.5f});
  env.step(action, obs);
  CHECK(obs == std::vector<float>{1.0f, -2.0f, 1.5f, 0.5f, 3.0f, -1.0f});
  env.step(action, obs);  // the oldest frame drops out
  CHECK(obs == std::vector<float>{1.5f, 0.5f, 3.0f, -1.0f, 1.5f, 0.5f});
  env.reset(std::nullopt, obs);
  CHECK(obs == std::vector<float>{0, 0, 0, 0, 1.0f, -2.0f});

  config.padding = "reset";
  FrameStack copies(script({{1.5f, 0.5f}}), config);
  copies.reset(std::nullopt, obs);
  CHECK(obs == std::vector<float>{1.0f, -2.0f, 1.0f, -2.0f, 1.0f, -2.0f});
  CHECK_THROWS_AS(from_yaml("{id: FrameStack, padding: same}", script({{0.0f, 0.0f}})),
                  std::invalid_argument);
  // Out-of-range values are refused when the config is parsed, with their position.
  CHECK_THROWS_WITH(from_yaml("{id: FrameStack, n_stack: 0}", script({{0.0f, 0.0f}})),
                    Catch::Contains("test.yaml:1:27: n_stack: must be in [1, 1000], got 0"));
}

TEST_CASE("TransformReward: scale, then offset, then clip", "[wrappers]") {
  auto make = [](double reward, const std::string& yaml) {
    EnvPtr env =
        from_yaml(yaml, std::make_unique<ScriptedEnv>(std::vector<std::vector<float>>{{0.0f, 0.0f}},
                                                      std::vector<std::vector<float>>{{0.0f, 0.0f}},
                                                      std::vector<double>{reward}, 100));
    std::vector<float> obs(2), action{0.0f};
    env->reset(std::nullopt, obs);
    return env->step(action, obs).reward;
  };
  CHECK(make(1.0, "{id: TransformReward, scale: 2, offset: 1}") == 3.0);
  CHECK(make(2.0, "{id: TransformReward, scale: 2, offset: 1, clip_max: 4}") == 4.0);
  CHECK(make(-3.0, "{id: TransformReward, scale: 0.5, clip_min: -1, clip_max: 1}") == -1.0);
  CHECK(make(0.25, "{id: TransformReward, clip_min: -1, clip_max: 1}") == 0.25);
  CHECK_THROWS_AS(make(0.0, "{id: TransformReward, clip_min: 1, clip_max: -1}"),
                  std::invalid_argument);
  CHECK_THROWS_WITH(make(0.0, "{id: TransformReward, scal: 2}"),
                    Catch::Contains("did you mean 'scale'"));
}

TEST_CASE("RewardShaping: obs_above_for penalises a streak of k steps above a threshold",
          "[wrappers]") {
  // x over the steps: 0.6 0.7 0.8 0.4 0.9 0.9 -> streak above 0.5: 1 2 3 0 1 2.
  const std::vector<std::vector<float>> xs{{0.6f, 0.0f}, {0.7f, 0.0f}, {0.8f, 0.0f},
                                           {0.4f, 0.0f}, {0.9f, 0.0f}, {0.9f, 0.0f}};
  auto rewards = [&](const std::string& yaml) {
    EnvPtr env = from_yaml(yaml, script(xs));
    std::vector<float> obs(2), action{0.0f};
    env->reset(std::nullopt, obs);
    std::vector<double> r;
    for (size_t t = 0; t < xs.size(); ++t) r.push_back(env->step(action, obs).reward);
    return r;
  };
  // Base reward 1 per step; the penalty applies from the 2nd step of each streak on.
  CHECK(rewards("{id: RewardShaping, terms: [{type: obs_above_for, index: 0, threshold: 0.5, "
                "steps: 2, penalty: -1.0}]}") == std::vector<double>{1, 0, 0, 1, 1, 0});
  CHECK(rewards("{id: RewardShaping, terms: [{type: obs_above_for, index: 0, threshold: 0.5, "
                "steps: 2, penalty: -1.0, repeat: false}]}") ==
        std::vector<double>{1, 0, 1, 1, 1, 0});
  CHECK(rewards("{id: RewardShaping, terms: [{type: obs_below_for, index: 0, threshold: 0.5, "
                "steps: 1, penalty: -2}]}") == std::vector<double>{1, 1, 1, -1, 1, 1});

  // A reset clears the streak: episodes of 2 steps never reach a streak of 3.
  EnvPtr short_episodes = from_yaml(
      "{id: RewardShaping, terms: [{type: obs_above_for, index: 0, threshold: 0.5, steps: 3, "
      "penalty: -1}]}",
      script(xs, 2));
  std::vector<float> obs(2), action{0.0f};
  for (int episode = 0; episode < 3; ++episode) {
    short_episodes->reset(std::nullopt, obs);
    for (int t = 0; t < 2; ++t) CHECK(short_episodes->step(action, obs).reward == 1.0);
  }
}

TEST_CASE("RewardShaping: per-step obs_abs, action_sq and constant terms add up", "[wrappers]") {
  EnvPtr env = from_yaml(
      "{id: RewardShaping, terms: [{type: obs_abs, index: 1, coef: -0.5}, "
      "{type: action_sq, coef: -0.25}, {type: constant, value: 0.125}]}",
      script({{0.0f, -3.0f}}, 100, 2));
  std::vector<float> obs(2), action{1.0f, 2.0f};
  env->reset(std::nullopt, obs);
  // 1 - 0.5 * |-3| - 0.25 * (1 + 4) + 0.125 = -1.625
  CHECK(env->step(action, obs).reward == -1.625);
  CHECK(dynamic_cast<RewardShaping&>(*env).last_shaping() == -2.625);
}

TEST_CASE("RewardShaping: strict parsing of terms", "[wrappers]") {
  auto build = [](const std::string& yaml) { return from_yaml(yaml, script({{0.0f, 0.0f}})); };
  CHECK_THROWS_WITH(build("{id: RewardShaping, terms: [{type: obs_abov_for, index: 0}]}"),
                    Catch::Contains("did you mean 'obs_above_for'"));
  CHECK_THROWS_WITH(build("{id: RewardShaping, terms: [{type: obs_above_for, treshold: 1}]}"),
                    Catch::Contains("did you mean 'threshold'"));
  // A key of another term type is not silently ignored.
  CHECK_THROWS_WITH(build("{id: RewardShaping, terms: [{type: constant, coef: 1}]}"),
                    Catch::Contains("unknown key 'coef'"));
  CHECK_THROWS_WITH(build("{id: RewardShaping, terms: [{index: 0}]}"),
                    Catch::Contains("missing `type`"));
  CHECK_THROWS_WITH(build("{id: RewardShaping, terms: [{type: obs_abs, index: 2, coef: -1}]}"),
                    Catch::Contains("index 2 is outside the observation"));
  CHECK_THROWS_WITH(build("{id: RewardShaping, terms: [{type: obs_above_for, steps: 0}]}"),
                    Catch::Contains("must be >= 1"));
  // The resolved form lists each term with its type's defaults.
  const ConfigNode node = ConfigNode::load_string(
      "{id: RewardShaping, terms: [{type: obs_above_for, index: 0, threshold: 0.5}]}", "test.yaml");
  const YAML::Node resolved =
      builtin_registry().wrapper("RewardShaping", node.child("id")).parse(node).resolved();
  CHECK(resolved["terms"][0]["type"].as<std::string>() == "obs_above_for");
  CHECK(resolved["terms"][0]["steps"].as<int>() == 1);
  CHECK(resolved["terms"][0]["penalty"].as<double>() == -1.0);
  CHECK_FALSE(resolved["terms"][0]["coef"].IsDefined());
}
