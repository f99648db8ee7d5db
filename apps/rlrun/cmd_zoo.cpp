// rlrun zoo import HYPERPARAMS.yml ENV_ID [-o FILE] [--algo ALGO]: an rl-baselines3-zoo
// hyperparameter entry as an rlrun experiment file (runtime/zoo/zoo_import.hpp, docs/zoo.md).
#include <cstdio>
#include <memory>

#include "commands.hpp"
#include "rlrun/core/errors.hpp"
#include "rlrun/runtime/run_directory.hpp"
#include "rlrun/runtime/zoo/zoo_import.hpp"

namespace rlrun::cli {

namespace {

struct ZooOptions {
  std::string hyperparams;
  std::string env_id;
  std::string output;
  std::string algo;
  std::string entry;  // another env's entry to use (--entry)
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
  import->add_option("--algo", options->algo,
                     "the algorithm, when the file name does not say (ppo, a2c, dqn, sac, td3, ddpg, tqc)");
  import->add_option("--entry", options->entry,
                     "use this entry's settings for env_id (e.g. PandaReach-v1 for GripperReach-v0)");
  return [options, &registry]() {
    const zoo::ZooImport imported = zoo::translate_zoo_entry(
        zoo::read_zoo_entry(options->hyperparams, options->env_id, options->algo, options->entry), registry);
    // Checked as `rlrun train` would check it, with the zoo file's positions in messages.
    parse_experiment(ConfigNode::from_yaml(imported.experiment, options->hyperparams), registry);
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
