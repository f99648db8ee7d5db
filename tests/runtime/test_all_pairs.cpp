// Every registered algorithm trains for a few hundred steps on every classic-control env,
// with env.auto_wrap adding DiscreteAsBox / BoxAsDiscrete where the action space needs it, and
// the saved model evaluates. (Issue: "any algorithm on any env", 6 x 5 pairs.)
#include <catch2/catch.hpp>
#include <filesystem>

#include "rlrun/core/errors.hpp"
#include "rlrun/runtime/components/builtins.hpp"
#include "rlrun/runtime/experiment/env_factory.hpp"
#include "rlrun/runtime/io/model_loader.hpp"
#include "rlrun/runtime/run/evaluator.hpp"
#include "rlrun/runtime/run/trainer.hpp"
#include "runtime/cli_runner.hpp"
#include "test_threads.hpp"

using namespace rlrun;

namespace {

bool has_param(const AlgorithmEntry& entry, const std::string& key) {
  for (const auto& row : entry.params())  // a section's rows are "policy.net_arch", ...
    if (row.key == key || row.key.starts_with(key + ".")) return true;
  return false;
}

// Small, fast settings for whichever of these keys the algorithm has.
std::string smoke_settings(const AlgorithmEntry& entry) {
  const std::pair<const char*, const char*> small[] = {{"n_steps", "32"},
                                                       {"batch_size", "32"},
                                                       {"buffer_size", "2000"},
                                                       {"learning_starts", "64"},
                                                       {"train_freq", "4"},
                                                       {"target_update_interval", "50"},
                                                       // MaskablePPO: classic envs have no masks
                                                       {"use_masking", "false"},
                                                       {"policy", "{net_arch: [16, 16]}"}};
  std::string out;
  for (const auto& [key, value] : small)
    if (has_param(entry, key)) out += std::string(", ") + key + ": " + value;
  return out;
}

}  // namespace

TEST_CASE("every algorithm trains on every classic env (auto_wrap) and its model evaluates",
          "[runtime][pairs]") {
  const Registry& registry = builtin_registry();
  testing::TempDir dir("pairs");
  int pairs = 0;
  for (const AlgorithmEntry& algo : registry.algorithms()) {
    for (const char* env_id : {"CartPole-v1", "Pendulum-v1", "MountainCar-v0",
                               "MountainCarContinuous-v0", "Acrobot-v1"}) {
      const std::string yaml = "run: {name: " + algo.id + "_" + env_id +
                               ", seed: 1, total_timesteps: 400, out_dir: " + dir.str() +
                               ", console_interval: 1000}\n"
                               "env: {id: " +
                               env_id +
                               ", n_envs: 2, auto_wrap: true}\n"
                               "algo: {id: " +
                               algo.id + smoke_settings(algo) + "}\n";
      INFO(algo.id << " on " << env_id << "\n" << yaml);
      const Experiment experiment =
          parse_experiment(ConfigNode::load_string(yaml, "pairs.yaml"), registry);
      const TrainOutcome outcome =
          train_experiment(experiment, registry, testing::test_execution());
      CHECK(outcome.timesteps >= 400);
      const ModelFile model = read_model(outcome.model_path);
      const Experiment stored = experiment_from_model(model, registry);
      EnvPtr env = make_env(stored.env, registry, "", 0.0);
      auto loaded = algorithm_from_model(model, stored, registry, env->observation_space(),
                                         env->action_space());
      const EvalResult r = evaluate_policy(*loaded, *env, 1, true, 3);
      CHECK(r.returns.size() == 1);
      ++pairs;
    }
  }
  CHECK(pairs == 5 * static_cast<int>(registry.algorithms().size()));
}

TEST_CASE("an action space the algorithm cannot use names the wrapper that fixes it",
          "[runtime][pairs]") {
  const Registry& registry = builtin_registry();
  for (const AlgorithmEntry& algo : registry.algorithms()) {
    const bool box = std::find(algo.action_spaces.begin(), algo.action_spaces.end(),
                               SpaceKind::kBox) != algo.action_spaces.end();
    const bool discrete = std::find(algo.action_spaces.begin(), algo.action_spaces.end(),
                                    SpaceKind::kDiscrete) != algo.action_spaces.end();
    if (box && discrete) continue;
    const std::string env_id = box ? "CartPole-v1" : "Pendulum-v1";
    const std::string yaml = "env: {id: " + env_id + "}\nalgo: {id: " + algo.id + "}\n";
    try {
      parse_experiment(ConfigNode::load_string(yaml, "mismatch.yaml"), registry);
      FAIL(algo.id << " accepted " << env_id);
    } catch (const ConfigError& e) {
      const std::string msg = e.what();
      INFO(msg);
      CHECK(msg.find("mismatch.yaml:1:11") != std::string::npos);
      CHECK(msg.find(box ? "DiscreteAsBox" : "BoxAsDiscrete") != std::string::npos);
      CHECK(msg.find("auto_wrap") != std::string::npos);
    }
  }
}
