#pragma once
// The experiment file (DESIGN.md §4), parsed strictly and resolved:
//   run:  {name, seed, total_timesteps, out_dir, log_interval}
//   env:  {id, n_envs, max_episode_steps, kwargs: {...}, wrappers: [{id: ..., ...}]}
//   algo: {id, <hyperparameters>, policy: {...}}
//   eval: {freq, n_episodes, deterministic}
// Every unknown key or id is a ConfigError with file:line:col and a did-you-mean. `resolved`
// holds the whole config with every default filled in; it is saved with the run and inside
// model files, so a model file alone can rebuild its env and policy.
#include <optional>
#include <string>
#include <vector>

#include "rlrun/core/config_node.hpp"
#include "rlrun/runtime/registry.hpp"

namespace rlrun {

struct RunConfig {
  std::string name;                 // default: the config file's stem
  uint64_t seed = 0;                // env i is seeded seed + i; all RNGs derive from it
  int64_t total_timesteps = 100000; // env steps over all envs, as SB3's learn(total_timesteps)
  std::string out_dir = "runs";     // run directory = <out_dir>/<name>/seed<seed>
  std::optional<int> log_interval;  // progress.csv rows every N iterations (on-policy) or
                                    // episodes (off-policy); null = SB3's default (1 / 4)
  double console_interval = 2.0;    // min seconds between console tables

  template <class V>
  void visit(V& v) {
    v("name", name, "run name (default: the config file name without .yaml)");
    v("seed", seed, "random seed; env i gets seed + i");
    v("total_timesteps", total_timesteps, "total env steps to train for (all envs together)");
    v("out_dir", out_dir, "root directory of run outputs");
    v("log_interval", log_interval,
      "progress.csv row every N iterations (on-policy) / episodes (off-policy); null = SB3 default");
    v("console_interval", console_interval, "minimum seconds between console summaries");
  }
};

struct EnvSectionConfig {
  int n_envs = 1;                          // parallel env copies (SB3 n_envs)
  std::optional<int> max_episode_steps;    // override the registered time limit
  bool auto_wrap = false;                  // add the action-space wrapper the algorithm needs
  template <class V>
  void visit(V& v) {
    v("n_envs", n_envs, "number of env copies stepped together");
    v("max_episode_steps", max_episode_steps, "time limit override (null = registered limit)");
    v("auto_wrap", auto_wrap,
      "wrap Discrete envs with DiscreteAsBox / Box envs with BoxAsDiscrete when the algorithm needs it");
  }
};

struct EvalConfig {
  int64_t freq = 0;         // total env steps between evaluations (0 = off)
  int n_episodes = 10;      // episodes per evaluation
  bool deterministic = true;
  template <class V>
  void visit(V& v) {
    v("freq", freq, "evaluate every `freq` TOTAL env steps (all envs counted; 0 = never)");
    v("n_episodes", n_episodes, "episodes per evaluation");
    v("deterministic", deterministic, "use the deterministic policy");
  }
};

struct EnvSpec {
  std::string id;
  ConfigNode id_node;
  EnvSectionConfig section;
  ConfigNode kwargs;
  std::vector<ConfigNode> wrappers;  // each a map with `id`
  // Set from the algorithm: the action spaces it supports and its id, for the check (and
  // auto_wrap) at the end of the env stack. Empty: no check.
  std::vector<SpaceKind> accepted_action_spaces;
  std::string algorithm_id;
};

struct Experiment {
  std::string source;  // the file it came from
  RunConfig run;
  EnvSpec env;
  std::string algo_id;
  ConfigNode algo_node;
  EvalConfig eval;
  YAML::Node resolved;
};

// Parses and validates (every id is looked up, every component's config read strictly).
Experiment parse_experiment(const ConfigNode& root, const Registry& registry);

// Loads a file, applies `--set` overrides, parses. The run name defaults to the file stem.
Experiment load_experiment(const std::string& path, const std::vector<std::string>& overrides,
                           const Registry& registry);

// Writes YAML text of a resolved config, in section order run, env, algo, eval.
std::string dump_yaml(const YAML::Node& node);

}  // namespace rlrun
