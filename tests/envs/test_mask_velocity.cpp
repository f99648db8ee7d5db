// rl-zoo's NoVel envs (env/mask_velocity.hpp): each is its base env with the velocity terms of
// MaskVelocityWrapper.velocity_indices multiplied by 0, step for step on the same seed and
// actions; the ids, time limits and kwargs of the base; Gymnasium's env checker; a policy
// trained on one through the CLI and exported with the mask in its graph.
#include <algorithm>
#include <catch2/catch.hpp>
#include <fstream>
#include <string>
#include <vector>

#include "rlrun/env/env_checker.hpp"
#include "rlrun/env/mask_velocity.hpp"
#include "rlrun/runtime/components/builtins.hpp"
#include "runtime/cli_runner.hpp"

using namespace rlrun;

namespace {

struct Masked {
  const char* base;
  const char* id;
  std::vector<int> velocities;
};

const std::vector<Masked> kMasked{
    {"CartPole-v1", "CartPoleNoVel-v1", {1, 3}},
    {"MountainCar-v0", "MountainCarNoVel-v0", {1}},
    {"MountainCarContinuous-v0", "MountainCarContinuousNoVel-v0", {1}},
    {"Pendulum-v1", "PendulumNoVel-v1", {2}},
    {"LunarLander-v3", "LunarLanderNoVel-v3", {2, 3, 5}},
    {"LunarLanderContinuous-v3", "LunarLanderContinuousNoVel-v3", {2, 3, 5}}};

EnvPtr build(const std::string& id) {
  const EnvEntry* entry = builtin_registry().find_env(id);
  REQUIRE(entry != nullptr);
  return entry->build(entry->parse(ConfigNode{}), EnvContext{});
}

}  // namespace

TEST_CASE("NoVel envs: the base env's observations with the velocities zeroed, step for step",
          "[envs][novel]") {
  for (const Masked& m : kMasked) {
    INFO(m.id);
    const EnvEntry* base_entry = builtin_registry().find_env(m.base);
    const EnvEntry* entry = builtin_registry().find_env(m.id);
    REQUIRE(entry != nullptr);
    CHECK(entry->max_episode_steps == base_entry->max_episode_steps);
    CHECK(entry->params().size() == base_entry->params().size());
    CHECK(entry->policies.empty());
    EnvPtr base = build(m.base), masked = build(m.id);
    CHECK(masked->id() == m.id);
    CHECK(masked->observation_space().describe() == base->observation_space().describe());
    const int dim = base->observation_space().flat_dim();
    std::vector<float> a(static_cast<size_t>(dim)), b(a.size()),
        action(static_cast<size_t>(base->action_space().flat_dim()));
    base->reset(7, a);
    masked->reset(7, b);
    Rng rng(3);
    int nonzero_velocity = 0;
    for (int t = 0; t < 60; ++t) {
      for (int i = 0; i < dim; ++i) {
        const bool velocity =
            std::find(m.velocities.begin(), m.velocities.end(), i) != m.velocities.end();
        CHECK(b[static_cast<size_t>(i)] == (velocity ? 0.0f : a[static_cast<size_t>(i)]));
        nonzero_velocity += velocity && a[static_cast<size_t>(i)] != 0.0f;
      }
      base->action_space().sample(rng, action);
      const StepResult ra = base->step(action, a);
      const StepResult rb = masked->step(action, b);
      CHECK(ra.reward == rb.reward);
      CHECK(ra.terminated == rb.terminated);
      if (ra.terminated) {
        base->reset(std::nullopt, a);
        masked->reset(std::nullopt, b);
      }
    }
    CHECK(nonzero_velocity > 0);  // there was something to mask
    CHECK(check_env(*masked).empty());
  }
  CHECK(no_velocity_id("Foo-v12") == "FooNoVel-v12");
  CHECK_THROWS_AS(MaskVelocity(build("CartPole-v1"), "x", {4}), std::invalid_argument);
}

TEST_CASE("NoVel envs: PPO trains on CartPoleNoVel-v1 and the export applies the mask",
          "[envs][novel][cli]") {
  testing::TempDir dir("novel_cli");
  const std::string config = dir / "exp.yaml";
  std::ofstream(config) << "run: {name: novel, seed: 1, total_timesteps: 256, out_dir: "
                        << dir.str()
                        << "}\nenv: {id: CartPoleNoVel-v1}\n"
                           "algo: {id: PPO, n_steps: 128, batch_size: 64, n_epochs: 1}\n";
  const auto train = testing::run_rlrun("train " + config);
  INFO(train.output);
  REQUIRE(train.exit_code == 0);
  const std::string model = dir / "novel/seed1/model.zip";
  const auto eval = testing::run_rlrun("eval --model " + model + " --episodes 2");
  INFO(eval.output);
  CHECK(eval.exit_code == 0);
  CHECK(eval.output.find("CartPoleNoVel-v1") != std::string::npos);
  const auto exported =
      testing::run_rlrun("export --model " + model + " --format onnx --output " + (dir / "p.onnx"));
  INFO(exported.output);
  CHECK(exported.exit_code == 0);
}
