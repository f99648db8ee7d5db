#pragma once
// rl-zoo entry -> rlrun experiment (`rlrun zoo import`, `rlrun train --zoo`): every key of the
// entry is translated as rl_zoo3/exp_manager.py reads it (_preprocess_hyperparams,
// _preprocess_normalization, _preprocess_action_noise, create_envs) or refused with the
// key's file:line:col; nothing is dropped silently. The table of what maps to what is in
// docs/zoo.md.
//
// A zoo file may come from anyone (docs/security.md): the translation is checked as text rlrun
// does not trust, like a model file's config. A value that starts a program, names a file to
// write or a simulator input keeps its default unless the user's own `--set` vouches for it;
// the env id is the user's (the command line names it). Error messages quote the file's text
// in bounded lines (core/quoted_text.hpp).
#include <string>
#include <vector>

#include <yaml-cpp/yaml.h>

#include "rlrun/runtime/components/registry.hpp"
#include "rlrun/runtime/experiment/experiment.hpp"
#include "rlrun/runtime/workflows/zoo/zoo_file.hpp"

namespace rlrun::zoo {

struct ZooImport {
  ZooEntry source;
  // The experiment (sections run, env, algo, eval). Values copied from the zoo file are its
  // own nodes, so a problem parse_experiment finds names the zoo file's line and column.
  YAML::Node experiment;
  std::vector<std::string> notes;      // what the written file's header says about the translation
  std::vector<std::string> overrides;  // the user's `--set` values applied (check_zoo_experiment)
};

// Translates `entry`. Throws ConfigError naming the zoo file, line and column of the first
// key it cannot translate (all such keys, one line each).
ZooImport translate_zoo_entry(const ZooEntry& entry, const Registry& registry);

// Checks the translation as `rlrun train` checks an experiment, as the zoo file's untrusted
// text (see above) with the env id vouched for, after applying `overrides` (the user's `--set`,
// also recorded in imported.overrides) to imported.experiment. Throws ConfigError (the zoo
// file's line and column, or the `--set`) naming the `--set` that vouches for a refused value.
Experiment check_zoo_experiment(ZooImport& imported, const std::vector<std::string>& overrides,
                                const Registry& registry);

// read_zoo_entry + translate_zoo_entry + check_zoo_experiment: what `rlrun train --zoo` trains.
Experiment load_zoo_experiment(const std::string& path, const std::string& env_id,
                               const std::string& algorithm,
                               const std::vector<std::string>& overrides, const Registry& registry,
                               const std::string& entry_name = "");

// The run name of `algorithm` on `env_id`: `ppo_CartPole-v1`. It is one plain path component
// (the run directory is <out_dir>/<name>/seed<N>), so each character of the env id outside
// [A-Za-z0-9._-] becomes '-' (`gymnasium:ALE/Pong-v5` -> `ppo_gymnasium-ALE-Pong-v5`), and at
// most 100 of them are kept.
std::string zoo_run_name(const std::string& algorithm, const std::string& env_id);

}  // namespace rlrun::zoo
