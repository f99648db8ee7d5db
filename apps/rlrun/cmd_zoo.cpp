// rlrun zoo import HYPERPARAMS.yml ENV_ID [-o FILE] [--algo ALGO] [--entry NAME] [--set K=V]...:
// an rl-baselines3-zoo hyperparameter entry as an rlrun experiment file
// (runtime/workflows/zoo/zoo_import.hpp, docs/zoo.md). The zoo file is untrusted, the written file the
// user's own: a value that names a program, a file to write or a simulator input is refused
// unless the user's `--set` vouches for it, and then written as set.
#include <cstdio>
#include <memory>

#include "commands.hpp"
#include "rlrun/core/errors.hpp"
#include "rlrun/runtime/io/run_directory.hpp"
#include "rlrun/runtime/workflows/zoo/experiment_text.hpp"
#include "rlrun/runtime/workflows/zoo/zoo_import.hpp"

namespace rlrun::cli {

namespace {

struct ZooOptions {
  std::string hyperparams;
  std::string env_id;
  std::string output;
  std::string algo;
  std::string entry;                   // another env's entry to use (--entry)
  std::vector<std::string> overrides;  // --set
};

}  // namespace

Action add_zoo(CLI::App& app, Registry& registry) {
  auto options = std::make_shared<ZooOptions>();
  CLI::App* zoo = app.add_subcommand("zoo", "rl-baselines3-zoo hyperparameter files (docs/zoo.md)");
  zoo->require_subcommand(1);
  CLI::App* import = zoo->add_subcommand(
      "import", "write an rlrun experiment file from a zoo hyperparams/<algo>.yml entry");
  import->add_option("hyperparams", options->hyperparams, "the zoo's hyperparams/<algo>.yml")
      ->required()
      ->check(CLI::ExistingFile);
  import->add_option("env_id", options->env_id, "the env whose entry to import (else `default`)")
      ->required();
  import->add_option("-o,--output", options->output, "write the experiment here (default: stdout)");
  import->add_option(
      "--algo", options->algo,
      "the algorithm, when the file name does not say (ppo, a2c, dqn, sac, td3, ddpg, tqc)");
  import->add_option(
      "--entry", options->entry,
      "use this entry's settings for env_id (e.g. PandaReach-v1 for GripperReach-v0)");
  import
      ->add_option("--set", options->overrides,
                   "set a value in the written file, e.g. --set run.seed=3 (repeatable); also "
                   "vouches for a value the zoo file may not set itself (docs/security.md)")
      ->allow_extra_args(false);
  return [options, &registry]() {
    zoo::ZooImport imported = zoo::translate_zoo_entry(
        zoo::read_zoo_entry(options->hyperparams, options->env_id, options->algo, options->entry),
        registry);
    // Checked as `rlrun train --zoo` checks it, with the zoo file's positions in messages.
    zoo::check_zoo_experiment(imported, options->overrides, registry);
    const std::string text = zoo::experiment_text(imported);
    if (options->output.empty()) {
      std::fputs(text.c_str(), stdout);
      return 0;
    }
    write_text_atomic(options->output, text);
    std::fprintf(stderr, "wrote %s (%s on %s, entry '%s')\n", options->output.c_str(),
                 imported.source.algorithm.c_str(), imported.source.env_id.c_str(),
                 imported.source.entry_name.c_str());
    return 0;
  };
}

}  // namespace rlrun::cli
