// The plugin mechanism in-process: an env written against the public API (include/rlrun/)
// and registered through the same entry-function contract a plugin library exports, then
// built through the registry like any env (strict kwargs, resolved config, docs), adapted
// to rlrun's Env (spaces, info), checked by the env checker; version mismatches and id
// clashes are refused with clear messages. test_plugin_example.cpp loads a real library.
#include <catch2/catch.hpp>
#include <string>
#include <vector>

#include "rlrun/core/errors.hpp"
#include "rlrun/env/env_checker.hpp"
#include "rlrun/plugin.hpp"
#include "rlrun/runtime/components/builtins.hpp"
#include "rlrun/runtime/components/plugin_env.hpp"
#include "rlrun/runtime/components/plugin_loader.hpp"

using namespace rlrun;

namespace {

// Counts up with action 1, down with action 0; reaching `target` ends the episode.
class CounterEnv : public EnvBase {
 public:
  struct Config {
    int target = 3;
    double reward = 1.0;
    std::vector<double> start_range = {0.0, 1.0};
    template <class V>
    void visit(V& v) {
      v("target", target, "count at which the episode ends");
      v("reward", reward, "reward on reaching the target");
      v("start_range", start_range, "uniform start in [lo, hi)");
    }
  };
  explicit CounterEnv(const Config& config) : config_(config) {
    if (config_.target < 1) throw std::invalid_argument("target must be >= 1");
    observation_space_ = Space::box(-100.0f, 100.0f, {1});
    action_space_ = Space::discrete(2);
    success_ = info_.add_key("is_success");
  }
  void reset(std::optional<uint64_t> seed, std::span<float> obs) override {
    seeding_.on_reset(seed);
    count_ = seeding_.rng().uniform(config_.start_range[0], config_.start_range[1]);
    info_.clear();
    obs[0] = static_cast<float>(count_);
  }
  StepResult step(std::span<const float> action, std::span<float> obs) override {
    count_ += action[0] > 0.5f ? 1.0 : -1.0;
    const bool done = count_ >= config_.target;
    info_.clear();
    info_.set(success_, done ? 1.0 : 0.0);
    obs[0] = static_cast<float>(count_);
    return {done ? config_.reward : 0.0, done, false};
  }

 private:
  Config config_;
  double count_ = 0;
  int success_ = 0;
};

// No Config: default-constructed; its Box has low > high, which Space refuses.
class BrokenSpaceEnv : public EnvBase {
 public:
  BrokenSpaceEnv() {
    observation_space_ = Space::box(1.0f, -1.0f, {1});
    action_space_ = Space::discrete(2);
  }
  void reset(std::optional<uint64_t>, std::span<float> obs) override { obs[0] = 0; }
  StepResult step(std::span<const float>, std::span<float> obs) override {
    obs[0] = 0;
    return {};
  }
};

uint32_t version_one(uint32_t, api::Registrar*) { return 1; }

uint32_t wrong_version(uint32_t, api::Registrar* registrar) {
  // A plugin of another version must not touch the registrar (rlrun/plugin.hpp contract).
  (void)registrar;
  return RLRUN_PLUGIN_API_VERSION + 1;
}

ConfigNode yaml(const std::string& text) { return ConfigNode::load_string(text, "test.yaml"); }

}  // namespace

// The entry function a plugin library would export.
RLRUN_PLUGIN(registrar) {
  registrar.add_env<CounterEnv>("TestCounter-v0", "count to a target", 20);
  registrar.add_env<BrokenSpaceEnv>("TestBrokenSpace-v0", "invalid observation space");
}

TEST_CASE("plugin: registered envs work like built-ins", "[plugin]") {
  Registry registry = builtin_registry();
  register_plugin(&rlrun_plugin_register, "test-plugin", registry);
  const EnvEntry* entry = registry.find_env("TestCounter-v0");
  REQUIRE(entry != nullptr);
  CHECK(entry->max_episode_steps == 20);
  CHECK(entry->description.find("count to a target") == 0);
  CHECK(entry->plugin == "test-plugin");
  CHECK(registry.find_env("CartPole-v1")->plugin.empty());

  // Parameters: documented, resolved with defaults, read strictly.
  const auto docs = entry->params();
  REQUIRE(docs.size() == 3);
  CHECK(docs[0].key == "target");
  CHECK(docs[0].default_value == "3");
  const YAML::Node resolved = entry->parse(yaml("{target: 5}")).resolved();
  CHECK(resolved["target"].as<int>() == 5);
  CHECK(resolved["reward"].as<double>() == 1.0);
  CHECK_THROWS_WITH(entry->parse(yaml("{targte: 5}")), Catch::Contains("did you mean 'target'"));
  CHECK_THROWS_AS(entry->make(entry->parse(yaml("{target: 0}"))), std::invalid_argument);

  EnvPtr env = entry->make(entry->parse(yaml("{target: 2, reward: 5.0}")));
  CHECK(env->id() == "TestCounter-v0");
  CHECK(env->observation_space().describe() == "Box(-100.0, 100.0, (1,), float32)");
  CHECK(env->action_space().describe() == "Discrete(2)");
  // Info keys are visible before the first reset (the evaluator looks them up once).
  const int success = env->info().find("is_success");
  REQUIRE(success >= 0);
  std::vector<float> obs(1);
  env->reset(0, obs);
  const float up = 1.0f;
  StepResult r = env->step({&up, 1}, obs);
  CHECK_FALSE(r.terminated);
  CHECK(env->info().get(success) == 0.0);
  r = env->step({&up, 1}, obs);
  CHECK(r.terminated);
  CHECK(r.reward == 5.0);
  CHECK(env->info().get(success) == 1.0);
  CHECK(check_env(*env, 1, 200).empty());
}

TEST_CASE("plugin: invalid spaces, version mismatches and id clashes are refused", "[plugin]") {
  Registry registry = builtin_registry();
  register_plugin(&rlrun_plugin_register, "test-plugin", registry);
  CHECK_THROWS_WITH(
      registry.find_env("TestBrokenSpace-v0")->make(AnyConfig::of_yaml(YAML::Node(), YAML::Node())),
      Catch::Contains("TestBrokenSpace-v0: Space::box: low > high"));

  Registry fresh = builtin_registry();
  CHECK_THROWS_WITH(register_plugin(&wrong_version, "old.so", fresh),
                    Catch::Contains("old.so was built for rlrun plugin API version " +
                                    std::to_string(RLRUN_PLUGIN_API_VERSION + 1)) &&
                        Catch::Contains("rebuild the plugin"));
  CHECK(fresh.find_env("TestCounter-v0") == nullptr);
  // A plugin of API version 1 (rlrun::api::Env) is told what changed.
  CHECK_THROWS_WITH(register_plugin(&version_one, "v1.so", fresh),
                    Catch::Contains("derive from rlrun::Env") &&
                        Catch::Contains("examples/custom_env/go_left.cpp"));
  // Registering the same ids again clashes with the first registration.
  CHECK_THROWS_WITH(register_plugin(&rlrun_plugin_register, "again.so", registry),
                    Catch::Contains("'TestCounter-v0' is already registered by test-plugin"));
  CHECK_THROWS_AS(register_plugin(&rlrun_plugin_register, "again.so", registry), UsageError);
}

TEST_CASE("plugin: library paths and loading errors", "[plugin]") {
  Registry registry = builtin_registry();
  CHECK_THROWS_WITH(load_plugin("no/such/libplugin.so", registry), Catch::Contains("not found"));
  CHECK(resolve_plugin_path("libnot_here.so") == "libnot_here.so");  // left to the loader
  CHECK_THROWS_WITH(load_plugin("libnot_here_rlrun_test.so", registry),
                    Catch::Contains("cannot load plugin"));
  // A shared library without the entry function is not a plugin.
  CHECK_THROWS_WITH(load_plugin("libm.so.6", registry), Catch::Contains("is not an rlrun plugin"));
}
