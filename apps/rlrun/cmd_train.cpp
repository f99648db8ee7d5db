// rlrun train CONFIG... [--set key=value]... [--seed N]
#include <iostream>
#include <memory>

#include "commands.hpp"
#include "plugin_option.hpp"
#include "rlrun/core/errors.hpp"
#include "rlrun/runtime/builtins.hpp"
#include "rlrun/runtime/trainer.hpp"

namespace rlrun::cli {

Action add_train(CLI::App& app) {
  struct Options {
    std::vector<std::string> configs;
    std::vector<std::string> overrides;
    std::optional<uint64_t> seed;
    std::vector<std::string> plugins;
  };
  auto options = std::make_shared<Options>();
  CLI::App* sub = app.add_subcommand("train", "train an agent from one or more experiment files");
  sub->add_option("configs", options->configs, "experiment YAML files (trained one after another)")
      ->required()
      ->check(CLI::ExistingFile);
  sub->add_option("--set", options->overrides,
                  "override a config value, e.g. --set algo.learning_rate=3e-4 (repeatable)");
  sub->add_option("--seed", options->seed, "set run.seed (overrides the files)");
  add_plugin_option(sub, options->plugins);
  return [options]() {
    load_plugin_options(options->plugins);
    const Registry& registry = builtin_registry();
    std::vector<std::string> overrides = options->overrides;
    if (options->seed) overrides.push_back("run.seed=" + std::to_string(*options->seed));
    // Validate every file before training any: a typo in the last file should not surface
    // after hours of training on the first.
    std::vector<Experiment> experiments;
    for (const auto& path : options->configs)
      experiments.push_back(load_experiment(path, overrides, registry));
    install_interrupt_handlers();
    for (const auto& experiment : experiments) {
      const TrainOutcome outcome = train_experiment(experiment, registry);
      if (outcome.interrupted) {
        std::cout << "interrupted: the model so far is in " << outcome.model_path << std::endl;
        return 130;
      }
    }
    return 0;
  };
}

}  // namespace rlrun::cli
