// rlrun train CONFIG... [--set key=value]... [--seed N]
// rlrun train --resume RUN_DIR|CHECKPOINT [--timesteps N]
#include <iostream>
#include <memory>

#include "commands.hpp"
#include "plugin_option.hpp"
#include "rlrun/core/errors.hpp"
#include "rlrun/runtime/builtins.hpp"
#include "rlrun/runtime/trainer.hpp"

namespace rlrun::cli {

namespace {
// 130 (128 + SIGINT, as shells report it) for an interrupted run; the trainer has printed
// where its checkpoint is and how to resume.
int exit_code(const TrainOutcome& outcome) { return outcome.interrupted ? 130 : 0; }
}  // namespace

Action add_train(CLI::App& app) {
  struct Options {
    std::vector<std::string> configs;
    std::vector<std::string> overrides;
    std::optional<uint64_t> seed;
    std::vector<std::string> plugins;
    std::string resume;
  };
  auto options = std::make_shared<Options>();
  CLI::App* sub = app.add_subcommand("train", "train an agent from one or more experiment files");
  sub->add_option("configs", options->configs, "experiment YAML files (trained one after another)")
      ->check(CLI::ExistingFile);
  sub->add_option("--resume", options->resume,
                  "continue an interrupted run exactly: its run directory (newest checkpoint) or "
                  "a checkpoints/step_<N>.zip file");
  sub->add_option("--set", options->overrides,
                  "override a config value, e.g. --set algo.learning_rate=3e-4 (repeatable)");
  sub->add_option("--seed", options->seed, "set run.seed (overrides the files)");
  add_plugin_option(sub, options->plugins);
  return [options]() {
    load_plugin_options(options->plugins);
    const Registry& registry = builtin_registry();
    if (!options->resume.empty()) {
      // A resumed run is the same run: its config.yaml, except for how long it trains.
      if (!options->configs.empty() || options->seed)
        throw UsageError("--resume continues a run with its own config.yaml; do not pass "
                         "experiment files or --seed with it");
      for (const std::string& o : options->overrides)
        if (o.rfind("run.total_timesteps=", 0) != 0 && o.rfind("run.console_interval=", 0) != 0)
          throw UsageError("--resume cannot change '" + o +
                           "' (only run.total_timesteps and run.console_interval): an exact "
                           "resume needs the run's settings");
      const std::string checkpoint = resolve_resume_checkpoint(options->resume);
      const Experiment experiment = load_experiment(
          run_dir_of_checkpoint(checkpoint) + "/config.yaml", options->overrides, registry);
      install_interrupt_handlers();
      return exit_code(train_experiment(experiment, registry, checkpoint));
    }
    if (options->configs.empty())
      throw UsageError("train needs experiment files (rlrun train configs/x.yaml) or --resume RUN_DIR");
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
      if (outcome.interrupted) return exit_code(outcome);
    }
    return 0;
  };
}

}  // namespace rlrun::cli
