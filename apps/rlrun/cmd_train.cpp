// rlrun train CONFIG... [--set key=value]... [--seed N] [--timesteps N] [--out DIR]
//                       [--init-from MODEL] [-j N]
// rlrun train --resume RUN_DIR|CHECKPOINT [--timesteps N]
#include <iostream>
#include <memory>

#include "cli_values.hpp"
#include "commands.hpp"
#include "parallel_runs.hpp"
#include "plugin_option.hpp"
#include "rlrun/core/errors.hpp"
#include "rlrun/runtime/builtins.hpp"
#include "rlrun/runtime/trainer.hpp"

namespace rlrun::cli {

namespace {

struct TrainOptions {
  std::vector<std::string> configs;
  std::vector<std::string> overrides;
  std::optional<uint64_t> seed;
  std::optional<int64_t> timesteps;
  std::string out;
  std::string init_from;
  std::vector<std::string> plugins;
  std::string resume;
  int jobs = 1;
};

// 130 (128 + SIGINT, as shells report it) for an interrupted run; the trainer has printed
// where its checkpoint is and how to resume.
int exit_code(const TrainOutcome& outcome) { return outcome.interrupted ? 130 : 0; }

// The shorthand options as the overrides they stand for, so that config.yaml records them.
std::vector<std::string> all_overrides(const TrainOptions& o) {
  std::vector<std::string> overrides = o.overrides;
  if (o.seed) overrides.push_back("run.seed=" + std::to_string(*o.seed));
  if (o.timesteps) overrides.push_back("run.total_timesteps=" + std::to_string(*o.timesteps));
  if (!o.out.empty()) overrides.push_back("run.out_dir=" + o.out);
  if (!o.init_from.empty()) overrides.push_back("run.init_from=" + o.init_from);
  return overrides;
}

int resume(const TrainOptions& o, const Registry& registry) {
  // A resumed run is the same run: its config.yaml, except for how long it trains.
  if (!o.configs.empty() || o.seed || !o.out.empty() || !o.init_from.empty() || o.jobs != 1)
    throw UsageError("--resume continues a run with its own config.yaml; it takes no experiment "
                     "files, --seed, --out, --init-from or -j");
  const std::vector<std::string> overrides = all_overrides(o);
  for (const std::string& override : overrides)
    if (override.rfind("run.total_timesteps=", 0) != 0 &&
        override.rfind("run.console_interval=", 0) != 0)
      throw UsageError("--resume cannot change '" + override +
                       "' (only run.total_timesteps and run.console_interval): an exact resume "
                       "needs the run's settings");
  const std::string checkpoint = resolve_resume_checkpoint(o.resume);
  const Experiment experiment =
      load_experiment(run_dir_of_checkpoint(checkpoint) + "/config.yaml", overrides, registry);
  install_interrupt_handlers();
  return exit_code(train_experiment(experiment, registry, checkpoint));
}

}  // namespace

Action add_train(CLI::App& app) {
  auto options = std::make_shared<TrainOptions>();
  CLI::App* sub = app.add_subcommand("train", "train an agent from one or more experiment files");
  sub->add_option("configs", options->configs,
                  "experiment YAML files (trained one after another, or -j at once)")
      ->check(CLI::ExistingFile);
  sub->add_option("--set", options->overrides,
                  "override a config value, e.g. --set algo.learning_rate=3e-4 (repeatable)");
  sub->add_option("--seed", options->seed, "set run.seed (overrides the files)")
      ->check(seed_value());
  sub->add_option("--timesteps", options->timesteps, "set run.total_timesteps")
      ->transform(integer_in(1, std::numeric_limits<int64_t>::max()));
  sub->add_option("--out", options->out, "set run.out_dir (root of the run directories)");
  sub->add_option("--init-from", options->init_from,
                  "start from a trained model's weights (run.init_from): fine-tune it on this "
                  "experiment's env and wrappers");
  sub->add_option("-j,--jobs", options->jobs,
                  "train up to N experiment files at once, as processes with --threads 1 each")
      ->transform(integer_in(1));
  sub->add_option("--resume", options->resume,
                  "continue an interrupted run exactly: its run directory (newest checkpoint) or "
                  "a checkpoints/step_<N>.zip file");
  add_plugin_option(sub, options->plugins);
  return [options]() {
    load_plugin_options(options->plugins);
    const Registry& registry = builtin_registry();
    if (!options->resume.empty()) return resume(*options, registry);
    if (options->configs.empty())
      throw UsageError("train needs experiment files (rlrun train configs/x.yaml) or --resume RUN_DIR");
    const std::vector<std::string> overrides = all_overrides(*options);
    // Validate every file before training any: a typo in the last file should not surface
    // after hours of training on the first.
    std::vector<Experiment> experiments;
    for (const auto& path : options->configs)
      experiments.push_back(load_experiment(path, overrides, registry));
    if (options->jobs > 1 && options->configs.size() > 1) {
      std::vector<std::string> child_options;
      for (const std::string& override : overrides) {
        child_options.push_back("--set");
        child_options.push_back(override);
      }
      for (const std::string& plugin : options->plugins) {
        child_options.push_back("--plugin");
        child_options.push_back(plugin);
      }
      return train_in_parallel(options->configs, child_options, options->jobs);
    }
    install_interrupt_handlers();
    for (const auto& experiment : experiments) {
      const TrainOutcome outcome = train_experiment(experiment, registry);
      if (outcome.interrupted) return exit_code(outcome);
    }
    return 0;
  };
}

}  // namespace rlrun::cli
