#pragma once
// rl-zoo entry -> rlrun experiment (`rlrun zoo import`, `rlrun train --zoo`): every key of the
// entry is translated as rl_zoo3/exp_manager.py reads it (_preprocess_hyperparams,
// _preprocess_normalization, _preprocess_action_noise, create_envs) or refused with the
// key's file:line:col; nothing is dropped silently. The table of what maps to what is in
// docs/zoo.md.
#include <string>
#include <vector>

#include <yaml-cpp/yaml.h>

#include "rlrun/runtime/experiment.hpp"
#include "rlrun/runtime/registry.hpp"
#include "rlrun/runtime/zoo/zoo_file.hpp"

namespace rlrun::zoo {

struct ZooImport {
  ZooEntry source;
  // The experiment (sections run, env, algo, eval). Values copied from the zoo file are its
  // own nodes, so a problem parse_experiment finds names the zoo file's line and column.
  YAML::Node experiment;
  std::vector<std::string> notes;  // what the written file's header says about the translation
};

// Translates `entry`. Throws ConfigError naming the zoo file, line and column of the first
// key it cannot translate (all such keys, one line each).
ZooImport translate_zoo_entry(const ZooEntry& entry, const Registry& registry);

// read_zoo_entry + translate_zoo_entry + parse_experiment (with `--set` overrides applied):
// what `rlrun train --zoo` trains. Throws ConfigError with the zoo file's line and column.
Experiment load_zoo_experiment(const std::string& path, const std::string& env_id,
                               const std::string& algorithm,
                               const std::vector<std::string>& overrides, Registry& registry,
                               const std::string& entry_name = "");

// The experiment file text: a header comment (where it came from, rlrun version, date, notes)
// then the experiment, without the zoo file's YAML tags.
std::string experiment_text(const ZooImport& imported);

}  // namespace rlrun::zoo
