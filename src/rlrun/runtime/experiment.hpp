#pragma once
// The experiment file (DESIGN.md §4), parsed strictly and resolved:
//   run:  {name, seed, total_timesteps, out_dir, log_interval}
//   env:  {id, n_envs, max_episode_steps, kwargs: {...}, wrappers: [{id: ..., ...}]}
//   algo: {id, <hyperparameters>, policy: {...}}
//   eval: {freq, n_episodes, deterministic, reward_threshold, max_no_improvement_evals, min_evals}
//   checkpoint: {freq, keep}
//   obs_log: {freq, env}
//   video: {freq, n_episodes, deterministic, fps, width, height, overlay}
// Every unknown key or id is a ConfigError with file:line:col and a did-you-mean. `resolved`
// holds the whole config with every default filled in; it is saved with the run and inside
// model files, so a model file alone can rebuild its env and policy.
#include <optional>
#include <string>
#include <vector>

#include "rlrun/core/any_config.hpp"
#include "rlrun/core/config_checks.hpp"
#include "rlrun/core/config_node.hpp"
#include "rlrun/runtime/registry.hpp"

namespace rlrun {

// The largest video side: H.264 level 6.2 allows 8192 pixels, but a frame of 4096 x 4096
// already takes 48 MiB in RGB; no env draws more detail than that.
inline constexpr int kMaxVideoSide = 4096;

struct RunConfig {
  std::string name;                 // default: the config file's stem
  uint64_t seed = 0;                // env i is seeded seed + i; all RNGs derive from it
  int64_t total_timesteps = 100000; // env steps over all envs, as SB3's learn(total_timesteps)
  std::string out_dir = "runs";     // run directory = <out_dir>/<name>/seed<seed>
  std::optional<int> log_interval;  // progress.csv rows every N iterations (on-policy) or
                                    // episodes (off-policy); null = SB3's default (1 / 4)
  double console_interval = 2.0;    // min seconds between console tables
  std::string init_from;            // model file whose weights start the run (empty: none)

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
  }
};

// An upper bound on n_envs: each env holds a monitor file open (and a simulator may hold
// sockets); beyond a few thousand, the gain is nil on any CPU rlrun runs on.
inline constexpr int kMaxEnvs = 4096;

struct EnvSectionConfig {
  int n_envs = 1;                          // parallel env copies (SB3 n_envs)
  std::optional<int> max_episode_steps;    // override the registered time limit
  bool auto_wrap = false;                  // add the action-space wrapper the algorithm needs
  template <class V>
  void visit(V& v) {
    v("n_envs", n_envs, "number of env copies stepped together", in_range(1, kMaxEnvs));
    v("max_episode_steps", max_episode_steps,
      "time limit override (null = registered limit; to remove a limit, use a large number)",
      at_least(1));
    v("auto_wrap", auto_wrap,
      "wrap Discrete envs with DiscreteAsBox / Box envs with BoxAsDiscrete when the algorithm needs it");
  }
};

// runtime/eval_callback.hpp: SB3 EvalCallback + its two stop callbacks.
struct EvalConfig {
  int64_t freq = 0;         // total env steps between evaluations (0 = off)
  int n_episodes = 10;      // episodes per evaluation
  bool deterministic = true;
  std::optional<double> reward_threshold;       // stop once best mean reward >= this
  std::optional<int> max_no_improvement_evals;  // stop after more evals than this without a new best
  int min_evals = 0;                            // evaluations before counting no-improvement
  template <class V>
  void visit(V& v) {
    v("freq", freq, "evaluate every `freq` TOTAL env steps (all envs counted; 0 = never)",
      non_negative());
    v("n_episodes", n_episodes, "episodes per evaluation", in_range(1, 1000000));
    v("deterministic", deterministic, "use the deterministic policy");
    v("reward_threshold", reward_threshold,
      "stop training once the best mean eval reward >= this (SB3 StopTrainingOnRewardThreshold; null = never)");
    v("max_no_improvement_evals", max_no_improvement_evals,
      "stop when more than this many evaluations in a row bring no new best (SB3 "
      "StopTrainingOnNoModelImprovement; null = never)",
      non_negative());
    v("min_evals", min_evals, "evaluations before no-improvement is counted", non_negative());
  }
};

// runtime/checkpoint_callback.hpp: SB3 CheckpointCallback.
struct CheckpointConfig {
  int64_t freq = 0;  // total env steps between checkpoints (0 = off)
  int keep = 0;      // newest checkpoints kept (0 = all)
  template <class V>
  void visit(V& v) {
    v("freq", freq, "write checkpoints/step_<N>.zip every `freq` TOTAL env steps (0 = never)",
      non_negative());
    v("keep", keep, "keep only the newest `keep` checkpoints (0 = keep all)", non_negative());
  }
};

// runtime/obs_log_callback.hpp: the course's ObsSaveCallback.
struct ObsLogConfig {
  int64_t freq = 0;  // total env steps between .npy chunks (0 = off)
  int env = 0;       // which training env's observations are logged
  template <class V>
  void visit(V& v) {
    v("freq", freq,
      "save the observations of training env `env` to obs_log/obs_<N>.npy every `freq` TOTAL env steps (0 = off)",
      non_negative());
    v("env", env, "index of the training env whose observations are logged", non_negative());
  }
};

// runtime/video_callback.hpp: an mp4 of evaluation episodes every `freq` steps.
struct VideoConfig {
  int64_t freq = 0;            // total env steps between videos (0 = off)
  int n_episodes = 1;          // episodes per video
  bool deterministic = true;
  std::optional<double> fps;   // null = the env's render fps
  int width = 0, height = 0;   // 0 = the env's frame size
  bool overlay = true;         // env id, episode, step, return
  template <class V>
  void visit(V& v) {
    v("freq", freq, "record videos/step_<N>.mp4 every `freq` TOTAL env steps (0 = never; needs ffmpeg)",
      non_negative());
    v("n_episodes", n_episodes, "evaluation episodes per video", in_range(1, 10000));
    v("deterministic", deterministic, "use the deterministic policy");
    v("fps", fps, "frames per second (null = the env's, e.g. 50 for CartPole)",
      in_range(0, 1000).open_low());
    v("width", width, "frame width in pixels (0 = the env's, e.g. 600)",
      in_range(0, kMaxVideoSide));
    v("height", height, "frame height in pixels (0 = the env's, e.g. 400)",
      in_range(0, kMaxVideoSide));
    v("overlay", overlay, "draw env id, episode, step and return on the frames");
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

// Parses and checks a whole experiment: every section is decoded once into its typed Config;
// ids, values, value constraints, wrapper parameters, algorithm/space compatibility (one env is
// built to learn its spaces) and resource bounds are checked before anything runs. All problems
// of the file come in one ConfigError, one line each with file:line:col. Plugins must be in
// `registry` already (load_experiment loads a trusted file's; docs/security.md).
Experiment parse_experiment(const ConfigNode& root, const Registry& registry);

// Loads a file, applies `--set` overrides, loads the plugins a trusted file names into
// `registry`, parses. The run name defaults to the file stem.
Experiment load_experiment(const std::string& path, const std::vector<std::string>& overrides,
                           Registry& registry, ConfigTrust trust = ConfigTrust::kUser);

// The spec of env `id` with its default parameters (env_by_id, tests). `origin` names it in
// messages. Throws ConfigError for an unknown id.
EnvSpec default_env_spec(const std::string& id, const Registry& registry,
                         const std::string& origin);

// Writes YAML text of a resolved config, in section order run, env, algo, eval, ...
std::string dump_yaml(const YAML::Node& node);

}  // namespace rlrun
