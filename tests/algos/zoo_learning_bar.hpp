#pragma once
// The hidden learning bars of sb3-contrib's algorithms (tests/algos/test_trpo.cpp,
// test_ars.cpp): a shipped zoo config trained with seeds 1-3, each final model evaluated on 20
// deterministic episodes from seed 1000; the bar holds when 2 of 3 seeds reach it.
#include <catch2/catch.hpp>
#include <cstdio>
#include <string>

#include "rlrun/runtime/components/builtins.hpp"
#include "rlrun/runtime/experiment/env_factory.hpp"
#include "rlrun/runtime/io/model_loader.hpp"
#include "rlrun/runtime/run/evaluator.hpp"
#include "rlrun/runtime/run/trainer.hpp"
#include "runtime/cli_runner.hpp"
#include "test_paths.hpp"
#include "test_threads.hpp"

namespace rlrun::testing {

// `config` relative to the source directory, e.g. configs/zoo/cartpole_trpo.yaml.
inline void check_zoo_learning_bar(const std::string& config, double bar) {
  int passed = 0;
  for (uint64_t seed : {1, 2, 3}) {
    TempDir dir("zoo_bar_" + std::to_string(seed));
    Registry registry = make_builtin_registry();
    const Experiment e =
        load_experiment(std::string(RLRUN_SOURCE_DIR) + "/" + config,
                        {"run.out_dir=" + dir.str(), "run.seed=" + std::to_string(seed)}, registry);
    const TrainOutcome outcome = train_experiment(e, builtin_registry(), test_execution());
    const ModelFile model = read_model(outcome.model_path);
    const Experiment stored = experiment_from_model(model, builtin_registry());
    EnvPtr env = make_env(stored.env, builtin_registry(), "", 0.0);
    auto loaded = algorithm_from_model(model, stored, builtin_registry(), env->observation_space(),
                                       env->action_space());
    const double mean = evaluate_policy(*loaded, *env, 20, true, 1000).mean_return();
    std::printf("%s seed %llu: %.1f s, eval %.1f\n", config.c_str(),
                static_cast<unsigned long long>(seed), outcome.wall_seconds, mean);
    passed += mean >= bar;
  }
  INFO(config);
  CHECK(passed >= 2);
}

}  // namespace rlrun::testing
