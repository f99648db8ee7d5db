#pragma once
// The experiment file (docs/experiments.md), parsed strictly and resolved:
//   run:  {name, seed, total_timesteps, out_dir, log_interval, tensorboard_log, ...}
//   env:  {id, n_envs, max_episode_steps, kwargs: {...}, wrappers: [{id: ..., ...}]}
//   algo: {id, <hyperparameters>, policy: {...}}
//   eval, checkpoint, obs_log, video, self_play: the callbacks' sections
// Each section is plain data in a header of its own beside this one (run_config.hpp,
// env_spec.hpp, eval_config.hpp, ...); this file reads a whole file into them.
// Every unknown key or id is a ConfigError with file:line:col and a did-you-mean. `resolved`
// holds the whole config with every default filled in; it is saved with the run and inside
// model files, so a model file alone can rebuild its env and policy.
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "rlrun/core/any_config.hpp"
#include "rlrun/core/config_checks.hpp"
#include "rlrun/core/config_node.hpp"
#include "rlrun/core/trusted_values.hpp"
#include "rlrun/env/env_spaces.hpp"
#include "rlrun/runtime/components/registry.hpp"
#include "rlrun/runtime/experiment/checkpoint_config.hpp"
#include "rlrun/runtime/experiment/env_spec.hpp"
#include "rlrun/runtime/experiment/eval_config.hpp"
#include "rlrun/runtime/experiment/obs_log_config.hpp"
#include "rlrun/runtime/experiment/run_config.hpp"
#include "rlrun/runtime/experiment/self_play_config.hpp"
#include "rlrun/runtime/experiment/video_config.hpp"

namespace rlrun {

struct AlgoSpec {
  std::string id;
  std::string where;  // "file:line:col" of algo.id
  AnyConfig params;   // the algorithm's Config
};

struct Experiment {
  std::string source;  // the file it came from
  RunConfig run;
  EnvSpec env;
  AlgoSpec algo;
  EvalConfig eval;
  CheckpointConfig checkpoint;
  ObsLogConfig obs_log;
  VideoConfig video;
  SelfPlayConfig self_play;
  std::vector<std::string> plugins;  // the libraries the env needs (absolute paths)
  YAML::Node resolved;
};

// What parsing knows of the env beyond the file.
struct ParseOptions {
  // The env's spaces as a model file recorded them: the algorithm is checked against these,
  // and the env is neither built nor asked (runtime/io/model_file.hpp).
  std::optional<EnvSpaces> recorded_env_spaces;
  // The env will never be built, only stood for by its recorded spaces (loading a model for
  // predict or export: make_spaces_only_env). Its kwargs are kept as written, unchecked: they
  // build nothing, so nothing in them needs vouching, and an env id this build does not
  // register is no error. Needs recorded_env_spaces.
  bool env_not_built = false;
};

// Parses and checks a whole experiment: every section is decoded once into its typed Config;
// ids, values, value constraints, wrapper parameters, algorithm/space compatibility (against
// the spaces the env's entry declares: env/env_entry.hpp; an env whose spaces only its running
// worker knows is checked by make_algorithm) and resource bounds are checked before anything
// runs. All problems of the file come in one ConfigError, one line each with file:line:col.
// Plugins must be in `registry` already (load_experiment loads a trusted file's;
// docs/security.md).
Experiment parse_experiment(const ConfigNode& root, const Registry& registry,
                            const ParseOptions& options = {});

// Loads a file, applies `--set` overrides, loads the plugins a trusted file names into
// `registry`, parses. The run name defaults to the file stem.
Experiment load_experiment(const std::string& path, const std::vector<std::string>& overrides,
                           Registry& registry, ConfigTrust trust = ConfigTrust::kUser);
// The same for an experiment the user gives as YAML text (the Python package's
// rlrun.train(dict), python/): `origin` names it in messages ("<origin>:line:col"), and the run
// name defaults to `default_name`.
Experiment load_experiment_text(const std::string& text, const std::string& origin,
                                const std::string& default_name,
                                const std::vector<std::string>& overrides, Registry& registry);

// The spec of env `id` with its default parameters (env_by_id, tests), or with `env.*`
// overrides from the command line (`--set env.python=...`). `origin` names it in messages.
// Throws ConfigError for an unknown id or a bad override.
EnvSpec default_env_spec(const std::string& id, const Registry& registry, const std::string& origin,
                         const std::vector<std::string>& overrides = {});

// The experiment's algorithm, fresh, for envs of `setup`'s spaces (the trainer's, and the probes
// that size what a checkpoint may hold), after the algorithm's checks against those spaces
// (AlgorithmEntry::check, as parsing runs them). Throws ConfigError (file:line:col of the algo
// section) for a configuration the algorithm refuses.
std::unique_ptr<Algorithm> make_algorithm(const Experiment& experiment, const Registry& registry,
                                          const AlgorithmSetup& setup);

// Writes YAML text of a resolved config, in section order run, env, algo, eval, ...
std::string dump_yaml(const YAML::Node& node);

}  // namespace rlrun
