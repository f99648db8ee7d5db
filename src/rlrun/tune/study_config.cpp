#include "rlrun/tune/study_config.hpp"

#include <yaml-cpp/yaml.h>

#include <filesystem>

#include "rlrun/core/config_fields.hpp"
#include "rlrun/core/errors.hpp"
#include "rlrun/runtime/experiment/experiment.hpp"
#include "rlrun/runtime/workflows/sbatch_script.hpp"

namespace rlrun::tune {

namespace fs = std::filesystem;

namespace {

// The study file as written; StudyConfig is what it resolves to.
struct StudyFile {
  std::string name;
  std::string base;
  std::string out_dir;
  std::string storage;
  int n_trials = 100;
  int seeds_per_trial = 1;
  std::optional<int64_t> n_timesteps;
  std::optional<int> n_evaluations;
  int eval_episodes = 5;
  std::optional<double> timeout;
  ObjectiveConfig objective;
  SamplerConfig sampler;
  PrunerConfig pruner;
  ConfigNode space;
  ConfigNode set;
  SlurmOptions slurm;

  template <class V>
  void visit(V& v) {
    v("name", name, "the study's name in the journal (default: the file's stem)");
    v("base", base, "the experiment file every trial starts from (relative to this file)");
    v("out_dir", out_dir, "where study.journal and trials/ go (default runs/tune/<name>)");
    v("storage", storage,
      "the study journal (Optuna's JournalFileStorage; default <out_dir>/study.journal)");
    v("n_trials", n_trials, "trials in total, over all workers and restarts", in_range(1, 1000000));
    v("seeds_per_trial", seeds_per_trial, "seeds each trial trains (run.seed, run.seed + 1, ...)",
      in_range(1, 100));
    v("n_timesteps", n_timesteps, "env steps per seed (null: the base's run.total_timesteps)",
      in_range(1, 1e15));
    v("n_evaluations", n_evaluations,
      "evaluations per seed, each an intermediate value for the pruner (null: the zoo's "
      "max(1, n_timesteps // 100000))",
      in_range(1, 100000));
    v("eval_episodes", eval_episodes, "episodes per evaluation (the zoo's --eval-episodes)",
      in_range(1, 1000000));
    v("timeout", timeout, "seconds per worker after which it starts no new trial (null: none)",
      greater_than(0));
    v("objective", objective, "what a trial's value is");
    v("sampler", sampler, "how parameters are chosen");
    v("pruner", pruner, "when a trial stops early");
    v("space", space, "zoo, or a map of parameters (docs/tune.md)");
    v("set", set, "key: value overrides for every trial");
    v("slurm", slurm, "sbatch options for `rlrun tune --slurm`");
  }
};

// The keys StudyConfig::seed_overrides sets in every trial's run, with the study's own way to
// choose each: a fixed override (`set:` or --set) of one would be replaced without a word.
struct PerTrialKey {
  const char* key;
  const char* instead;
};
constexpr PerTrialKey kPerTrialKeys[] = {
    {"run.out_dir", "trials train into the study's <out_dir>/trials/ (out_dir, or --out DIR)"},
    {"run.name", "each trial's runs are named trial_<N>"},
    {"eval.freq", "each seed evaluates n_evaluations times, evenly spread (set n_evaluations)"},
    {"eval.n_episodes", "each evaluation runs eval_episodes episodes (set eval_episodes)"},
    {"checkpoint.freq", "trials keep no checkpoints (a killed trial runs again from its start)"},
};

// Why a fixed override of `key` to `value` would not reach the trials ("" when it would).
// run.total_timesteps is every trial's step count unless the study names one: n_timesteps in
// the file, or --n-timesteps.
std::string per_trial_problem(const std::string& key, const std::string& value,
                              const ConfigNode& root, std::optional<int64_t> n_timesteps_option) {
  for (const PerTrialKey& k : kPerTrialKeys)
    if (key == k.key) return "the study sets " + key + " for every trial: " + k.instead;
  if (key != "run.total_timesteps") return "";
  if (n_timesteps_option)
    return "--n-timesteps " + std::to_string(*n_timesteps_option) +
           " gives every trial its steps; leave out this override";
  const ConfigNode n_timesteps = root.child("n_timesteps");
  if (!n_timesteps.defined()) return "";  // the base's run.total_timesteps, this override's
  return "the study's n_timesteps (" + n_timesteps.yaml().Scalar() + ", " + n_timesteps.where() +
         ") gives every trial its steps and would replace it; use --n-timesteps " + value +
         " (or change n_timesteps)";
}

}  // namespace

std::vector<std::string> StudyConfig::seed_overrides(const std::vector<Override>& params,
                                                     int trial_number, int seed_index) const {
  std::vector<std::string> out;
  for (const Override& o : set) out.push_back(o.assignment());
  for (const Override& o : params) out.push_back(o.assignment());
  out.push_back("run.seed=" + std::to_string(base_seed + static_cast<uint64_t>(seed_index)));
  out.push_back("run.total_timesteps=" + std::to_string(n_timesteps));
  out.push_back("run.out_dir=" + yaml_double_quoted((fs::path(out_dir) / "trials").string()));
  out.push_back("run.name=" + yaml_double_quoted("trial_" + std::to_string(trial_number)));
  // rl-zoo's TrialEvalCallback: n_evaluations evaluations over the run, deterministic.
  out.push_back("eval.freq=" + std::to_string(std::max<int64_t>(n_timesteps / n_evaluations, 1)));
  out.push_back("eval.n_episodes=" + std::to_string(eval_episodes));
  // A trial's checkpoints would only fill the disk: a killed trial is run again from the start.
  out.push_back("checkpoint.freq=0");
  return out;
}

std::string StudyConfig::trial_dir(int trial_number) const {
  return (fs::path(out_dir) / "trials" / ("trial_" + std::to_string(trial_number))).string();
}

StudyConfig load_study(const std::string& path, Registry& registry,
                       const std::vector<std::string>& set, const std::string& out_dir,
                       std::optional<int64_t> n_timesteps) {
  if (!fs::exists(path)) throw UsageError(path + " does not exist");
  const ConfigNode root = ConfigNode::load_file(path);
  StudyFile file;
  decode(root, file);
  check_slurm_options(root.child("slurm"), file.slurm);
  if (file.base.empty()) root.fail("base: missing (the experiment file every trial starts from)");

  StudyConfig study;
  study.source = fs::absolute(path).lexically_normal().string();
  const fs::path here = fs::path(path).parent_path();
  study.base =
      fs::absolute(fs::path(file.base).is_absolute() ? fs::path(file.base) : here / file.base)
          .lexically_normal()
          .string();
  if (!fs::exists(study.base)) root.child("base").fail(study.base + " does not exist");
  study.name = file.name.empty() ? fs::path(path).stem().string() : file.name;
  const std::string chosen_out = out_dir.empty() ? file.out_dir : out_dir;
  study.out_dir =
      fs::absolute(chosen_out.empty() ? fs::path("runs/tune") / study.name : fs::path(chosen_out))
          .lexically_normal()
          .string();
  study.storage = file.storage.empty() || !out_dir.empty()
                      ? (fs::path(study.out_dir) / "study.journal").string()
                      : fs::absolute(file.storage).lexically_normal().string();
  study.n_trials = file.n_trials;
  study.seeds_per_trial = file.seeds_per_trial;
  study.eval_episodes = file.eval_episodes;
  study.timeout = file.timeout;
  study.objective = file.objective;
  study.sampler = file.sampler;
  study.pruner = file.pruner;
  study.slurm = file.slurm;

  // Fixed overrides: the file's `set:`, then the command line's; each checked against the base
  // so that a typo points at its own line.
  if (file.set.defined()) {
    if (!file.set.is_map()) file.set.fail("expected a map of key: value");
    for (const std::string& key : file.set.keys()) {
      Override o{key, yaml_override_text(file.set.child(key).yaml())};
      if (const std::string problem = per_trial_problem(key, o.yaml, root, n_timesteps);
          !problem.empty())
        file.set.fail_at_key(key, problem);
      try {
        load_experiment(study.base, {o.assignment()}, registry);
      } catch (const ConfigError& e) {
        file.set.fail_at_key(key, o.assignment() + " does not fit " + study.base + ": " + e.what());
      }
      study.set.push_back(o);
    }
  }
  for (const std::string& assignment : set) {
    const size_t eq = assignment.find('=');
    if (eq == std::string::npos || eq == 0)
      throw UsageError("--set " + assignment + ": expected key=value");
    const std::string key = assignment.substr(0, eq), value = assignment.substr(eq + 1);
    if (const std::string problem = per_trial_problem(key, value, root, n_timesteps);
        !problem.empty())
      throw UsageError("--set " + assignment + ": " + problem);
    study.set.push_back({key, value});
  }
  std::vector<std::string> fixed;
  for (const Override& o : study.set) fixed.push_back(o.assignment());
  const Experiment base = load_experiment(study.base, fixed, registry);
  study.base_seed = base.run.seed;
  study.algo_id = base.algo.id;
  study.n_timesteps = n_timesteps.value_or(file.n_timesteps.value_or(base.run.total_timesteps));
  study.n_evaluations = file.n_evaluations.value_or(
      static_cast<int>(std::max<int64_t>(1, study.n_timesteps / 100000)));
  if (study.n_evaluations > study.n_timesteps)
    root.child("n_evaluations").fail("more evaluations than env steps per seed");
  if (!study.sampler.seed) study.sampler.seed = base.run.seed;

  const YAML::Node her = base.resolved["algo"]["replay_buffer_class"];
  const bool uses_her = her && her.IsScalar() && her.Scalar() == "HerReplayBuffer";
  study.space = parse_space(file.space, study.algo_id, uses_her);
  return study;
}

}  // namespace rlrun::tune
