#pragma once
// The experiment file (docs/experiments.md), parsed strictly and resolved:
//   run:  {name, seed, total_timesteps, out_dir, log_interval, tensorboard_log, ...}
//   env:  {id, n_envs, max_episode_steps, kwargs: {...}, wrappers: [{id: ..., ...}]}
//   algo: {id, <hyperparameters>, policy: {...}}
//   eval, checkpoint, obs_log, video: the callbacks' sections (each Config is in its
//   callback's header: runtime/eval_callback.hpp, checkpoint_callback.hpp, ...)
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
#include "rlrun/runtime/checkpoint_callback.hpp"
#include "rlrun/runtime/eval_callback.hpp"
#include "rlrun/runtime/obs_log_callback.hpp"
#include "rlrun/runtime/registry.hpp"
#include "rlrun/runtime/video_callback.hpp"
#include "rlrun/wrappers/vec_normalize.hpp"

namespace rlrun {


struct RunConfig {
  std::string name;                 // default: the config file's stem
  uint64_t seed = 0;                // env i is seeded seed + i; all RNGs derive from it
  int64_t total_timesteps = 100000; // env steps over all envs, as SB3's learn(total_timesteps)
  std::string out_dir = "runs";     // run directory = <out_dir>/<name>/seed<seed>
  std::optional<int> log_interval;  // progress.csv rows every N iterations (on-policy) or
                                    // episodes (off-policy); null = SB3's default (1 / 4)
  double console_interval = 2.0;    // min seconds between console tables
  std::string init_from;            // model file whose weights start the run (empty: none)
  OutputPath tensorboard_log;       // SB3's tensorboard_log: DIR for TensorBoard event files
  std::optional<std::string> tb_log_name;  // SB3's tb_log_name; null = the run name
  bool tensorboard_images = false;  // the learning curve as a TensorBoard image at the end

  template <class V>
  void visit(V& v) {
    v("name", name, "run name (default: the config file name without .yaml)", RelativeName{});
    v("seed", seed, "random seed; env i gets seed + i");
    v("total_timesteps", total_timesteps, "total env steps to train for (all envs together)",
      in_range(1, 1e15));
    v("out_dir", out_dir, "root directory of run outputs", DirectoryPath{});
    v("log_interval", log_interval,
      "progress.csv row every N iterations (on-policy) / episodes (off-policy); null = SB3 default",
      at_least(1));
    v("console_interval", console_interval, "minimum seconds between console summaries",
      in_range(0, 1e9));
    v("init_from", init_from,
      "model file whose weights (and normalisation statistics) start this run; empty = none");
    v("tensorboard_log", tensorboard_log,
      "directory for TensorBoard event files (SB3's tensorboard_log): each run writes "
      "DIR/<tb_log_name>_<N>/; empty = none");
    v("tb_log_name", tb_log_name,
      "name of this run's TensorBoard runs under tensorboard_log (null = the run name)",
      RelativeName{});
    v("tensorboard_images", tensorboard_images,
      "with tensorboard_log: add the learning curve as an image when the run finishes (off by "
      "default: drawing it costs about 60 ms, 7 % of a 1-second CartPole run)");
  }
};

// An upper bound on n_envs: each env holds a monitor file open (and a simulator may hold
// sockets); beyond a few thousand, the gain is nil on any CPU rlrun runs on.
inline constexpr int kMaxEnvs = 4096;

struct EnvSectionConfig {
  int n_envs = 1;                          // parallel env copies (SB3 n_envs)
  std::optional<int> max_episode_steps;    // override the registered time limit
  bool auto_wrap = false;                  // add the action-space wrapper the algorithm needs
  ProgramPath python{"python3"};           // interpreter of python:/gymnasium: envs
  double startup_timeout = 60.0;           // seconds their worker may take to build the env
  // SB3's Monitor info_keywords; null = the env's declared metrics (env/env_entry.hpp).
  std::optional<std::vector<std::string>> info_keywords;
  NormalizeSetting normalize;              // SB3 VecNormalize (wrappers/vec_normalize.hpp)
  template <class V>
  void visit(V& v) {
    v("n_envs", n_envs, "number of env copies stepped together", in_range(1, kMaxEnvs));
    v("max_episode_steps", max_episode_steps,
      "time limit override (null = registered limit; to remove a limit, use a large number)",
      at_least(1));
    v("auto_wrap", auto_wrap,
      "wrap Discrete envs with DiscreteAsBox / Box envs with BoxAsDiscrete when the algorithm needs it");
    v("python", python,
      "Python interpreter for python:/gymnasium: envs (a name on PATH or a path, e.g. a "
      "virtualenv's bin/python); the default python3 gives way to $RLRUN_PYTHON when set");
    v("startup_timeout", startup_timeout,
      "seconds a python:/gymnasium: env's worker may take to import its module and build the "
      "env (its __init__) before rlrun stops it with an error",
      in_range(0, 1e6).open_low());
    v("info_keywords", info_keywords,
      "info keys read at each episode's end: monitor.csv columns, rollout/<key> and eval/<key> "
      "means (SB3's Monitor info_keywords); null = the env's metrics and is_success, [] = none");
    v("normalize", normalize,
      "SB3 VecNormalize on the training envs (rl-zoo's normalize): true, or {norm_obs, "
      "norm_reward, clip_obs, clip_reward, gamma (null = the algorithm's), epsilon}");
  }
};





struct WrapperSpec {
  std::string id;
  AnyConfig params;
};

struct EnvSpec {
  std::string id;
  std::string where;  // "file:line:col" of env.id, for messages after parsing
  EnvSectionConfig section;
  AnyConfig kwargs;   // the env's Config (empty: its defaults)
  std::vector<WrapperSpec> wrappers;
  // Set from the algorithm: the action spaces it supports and its id, for the check (and
  // auto_wrap) at the end of the env stack. Empty: no check.
  std::vector<SpaceKind> accepted_action_spaces;
  std::string algorithm_id;
  // The algorithm's gamma, for env.normalize's `gamma: null` (unset: VecNormalize's 0.99).
  std::optional<double> algorithm_gamma;
  double normalize_gamma() const {
    return section.normalize.gamma.value_or(algorithm_gamma.value_or(0.99));
  }
};

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
  std::vector<std::string> plugins;  // the libraries the env needs (absolute paths)
  YAML::Node resolved;
};

// What parsing knows of the env beyond the file.
struct ParseOptions {
  // The env's spaces as a model file recorded them: the algorithm is checked against these,
  // and the env is neither built nor asked (runtime/model_file.hpp).
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
EnvSpec default_env_spec(const std::string& id, const Registry& registry,
                         const std::string& origin,
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
