// rlrun train CONFIG... [--set key=value]... [--seed N] [--timesteps N] [--out DIR]
//                       [--init-from MODEL] [--tensorboard-log DIR] [-j N]
// rlrun train --resume RUN_DIR|CHECKPOINT [--timesteps N] [--tensorboard-log DIR]
// rlrun train --zoo HYPERPARAMS.yml --env ENV_ID [--algo ALGO] [--set ...] (docs/zoo.md)
#include <filesystem>
#include <iostream>
#include <memory>
#include <sstream>

#include "cli_values.hpp"
#include "commands.hpp"
#include "parallel_runs.hpp"
#include "plugin_option.hpp"
#include "rlrun/core/dir_handle.hpp"
#include "rlrun/core/errors.hpp"
#include "rlrun/core/interrupt.hpp"
#include "rlrun/runtime/components/builtins.hpp"
#include "rlrun/runtime/io/run_lock.hpp"
#include "rlrun/runtime/run/resume_point.hpp"
#include "rlrun/runtime/run/trainer.hpp"
#include "rlrun/runtime/workflows/zoo/zoo_import.hpp"

namespace rlrun::cli {

namespace {

struct TrainOptions {
  std::vector<std::string> configs;
  std::vector<std::string> overrides;
  std::optional<uint64_t> seed;
  std::optional<int64_t> timesteps;
  std::string out;
  std::string init_from;
  std::string tensorboard_log;
  std::vector<std::string> plugins;
  std::string resume;
  int jobs = 1;
  std::string zoo;
  std::string zoo_env;
  std::string zoo_algo;
  std::string zoo_entry;
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
  if (!o.tensorboard_log.empty()) overrides.push_back("run.tensorboard_log=" + o.tensorboard_log);
  return overrides;
}

// True when `--set key=value` restates the value the run's config already has: the run is
// unchanged, and the user vouches for a value the untrusted config.yaml carries (a plugin's
// kwargs, a SUMO binary; docs/security.md).
bool restates(const ConfigNode& config, const std::string& assignment) {
  const auto eq = assignment.find('=');
  if (eq == std::string::npos) return false;
  ConfigNode node = config;
  std::stringstream path(assignment.substr(0, eq));
  for (std::string key; std::getline(path, key, '.');) node = node.child(key);
  if (!node.defined()) return false;
  try {
    return dump_yaml(node.yaml()) == dump_yaml(YAML::Load(assignment.substr(eq + 1)));
  } catch (const YAML::Exception&) {
    return false;
  }
}

int resume(const TrainOptions& o, Registry& registry, const ExecutionContext& execution) {
  // A resumed run is the same run: its config.yaml, except for how long it trains.
  if (!o.configs.empty() || o.seed || !o.out.empty() || !o.init_from.empty() || o.jobs != 1)
    throw UsageError(
        "--resume continues a run with its own config.yaml; it takes no experiment "
        "files, --seed, --out, --init-from or -j");
  std::error_code ec;
  const std::string run_dir =
      std::filesystem::is_directory(o.resume, ec) ? o.resume : run_dir_of_checkpoint(o.resume);
  const std::string config = run_dir + "/config.yaml";
  const std::vector<std::string> overrides = all_overrides(o);
  // A run directory may come from anyone: it must be a directory, not a link, its config.yaml
  // a regular file (core/dir_handle.hpp), and that config is untrusted (docs/security.md).
  bool has_config = false;
  if (std::filesystem::is_directory(run_dir, ec)) {
    const DirHandle dir = DirHandle::open(run_dir);
    has_config = static_cast<bool>(dir.open_for_reading("config.yaml"));
    // What a killed process left (the temporaries of atomic writes) goes now, also when it was
    // killed before its first checkpoint and there is nothing to resume from.
    const RunLock lock(dir);
    remove_stale_temporaries(dir);
  }
  const ConfigNode stored =
      has_config ? ConfigNode::load_file(config, ConfigTrust::kUntrusted) : ConfigNode();
  for (const std::string& override : overrides)
    if (override.rfind("run.total_timesteps=", 0) != 0 &&
        override.rfind("run.console_interval=", 0) != 0 && !restates(stored, override))
      throw UsageError("--resume cannot change '" + override +
                       "' (only run.total_timesteps and run.console_interval): an exact resume "
                       "needs the run's settings");
  const std::vector<std::string> candidates = resume_candidates(o.resume);
  const Experiment experiment =
      load_experiment(config, overrides, registry, ConfigTrust::kUntrusted);
  install_interrupt_handlers();
  return exit_code(train_experiment(experiment, registry, execution, candidates));
}

int train_zoo(const TrainOptions& o, Registry& registry, const ExecutionContext& execution) {
  if (!o.configs.empty() || o.jobs != 1)
    throw UsageError("--zoo trains one zoo entry; it takes no experiment files or -j");
  if (o.zoo_env.empty()) throw UsageError("--zoo needs --env ENV_ID (the entry to train)");
  const Experiment experiment = zoo::load_zoo_experiment(o.zoo, o.zoo_env, o.zoo_algo,
                                                         all_overrides(o), registry, o.zoo_entry);
  install_interrupt_handlers();
  return exit_code(train_experiment(experiment, registry, execution));
}

}  // namespace

Action add_train(CLI::App& app, Registry& registry, const ExecutionContext& execution) {
  auto options = std::make_shared<TrainOptions>();
  CLI::App* sub = app.add_subcommand("train", "train an agent from one or more experiment files");
  sub->add_option("configs", options->configs,
                  "experiment YAML files (trained one after another, or -j at once)")
      ->check(CLI::ExistingFile);
  sub->add_option("--set", options->overrides,
                  "override a config value, e.g. --set algo.learning_rate=3e-4 (repeatable)")
      ->allow_extra_args(false);
  sub->add_option("--seed", options->seed, "set run.seed (overrides the files)")
      ->check(seed_value());
  sub->add_option("--timesteps", options->timesteps, "set run.total_timesteps")
      ->transform(integer_in(1, std::numeric_limits<int64_t>::max()));
  sub->add_option("--out", options->out, "set run.out_dir (root of the run directories)");
  sub->add_option("--init-from", options->init_from,
                  "start from a trained model's weights (run.init_from): fine-tune it on this "
                  "experiment's env and wrappers");
  sub->add_option("--tensorboard-log", options->tensorboard_log,
                  "write TensorBoard event files under DIR (run.tensorboard_log; with --resume: "
                  "the run's own DIR, to continue its TensorBoard run)");
  sub->add_option("-j,--jobs", options->jobs,
                  "train up to N experiment files at once, as processes sharing --threads equally")
      ->transform(integer_in(1));
  sub->add_option("--resume", options->resume,
                  "continue an interrupted run exactly: its run directory (newest checkpoint) or "
                  "a checkpoints/step_<N>.zip file");
  sub->add_option(
         "--zoo", options->zoo,
         "train an rl-baselines3-zoo hyperparameter entry directly (hyperparams/<algo>.yml "
         "with --env; `rlrun zoo import` writes the same experiment as a file)")
      ->check(CLI::ExistingFile);
  sub->add_option("--env", options->zoo_env, "with --zoo: the env whose entry to train");
  sub->add_option("--algo", options->zoo_algo,
                  "with --zoo: the algorithm, when the file name does not say");
  sub->add_option("--zoo-entry", options->zoo_entry,
                  "with --zoo: use this entry's settings for --env (e.g. PandaReach-v1 for "
                  "GripperReach-v0)");
  add_plugin_option(sub, options->plugins);
  return [options, &registry, &execution]() {
    load_plugin_options(options->plugins, registry);
    if (!options->resume.empty()) return resume(*options, registry, execution);
    if (!options->zoo.empty()) return train_zoo(*options, registry, execution);
    if (!options->zoo_env.empty() || !options->zoo_algo.empty() || !options->zoo_entry.empty())
      throw UsageError("--env, --algo and --zoo-entry go with --zoo HYPERPARAMS.yml");
    if (options->configs.empty())
      throw UsageError(
          "train needs experiment files (rlrun train configs/x.yaml) or --resume RUN_DIR");
    const std::vector<std::string> overrides = all_overrides(*options);
    // Validate every file before training any: a typo in the last file should not surface
    // after hours of training on the first.
    // Every problem of every file is reported at once, before anything trains.
    std::vector<Experiment> experiments;
    std::string problems;
    for (const auto& path : options->configs) {
      try {
        experiments.push_back(load_experiment(path, overrides, registry));
      } catch (const ConfigError& e) {
        problems += (problems.empty() ? "" : "\n") + std::string(e.what());
      }
    }
    if (!problems.empty()) throw ConfigError(problems);
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
      return train_in_parallel(options->configs, child_options, options->jobs,
                               threads_per_job(execution, options->jobs));
    }
    install_interrupt_handlers();
    for (const auto& experiment : experiments) {
      const TrainOutcome outcome = train_experiment(experiment, registry, execution);
      if (outcome.interrupted) return exit_code(outcome);
    }
    return 0;
  };
}

}  // namespace rlrun::cli
