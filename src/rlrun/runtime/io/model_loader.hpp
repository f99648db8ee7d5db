#pragma once
// Loading a model file (model_file.hpp: the format and its two reading phases) into what the
// commands use: the experiment stored in it, its env with the stored statistics frozen, and
// its algorithm with the stored weights, within the byte budget of model_budget.hpp.
#include <memory>
#include <string>
#include <vector>

#include "rlrun/algos/algorithm.hpp"
#include "rlrun/env.hpp"
#include "rlrun/runtime/components/registry.hpp"
#include "rlrun/runtime/experiment/experiment.hpp"
#include "rlrun/runtime/io/model_file.hpp"
#include "rlrun/runtime/io/model_trust.hpp"

namespace rlrun {

// What the caller does with a model's env. kRun builds and steps it (eval, record, resume).
// kSpacesOnly only turns the model into a policy (predict, export): the env stands for the
// spaces the file records (make_spaces_only_env), so nothing the env would need (a Python
// worker, a scenario's files, a simulator this build left out) is started, read or required,
// and its kwargs need no vouching. Files written before rlrun recorded the spaces fall back
// to the env's declared spaces, or to building it.
enum class ModelEnv { kRun, kSpacesOnly };

// Rebuilds the experiment stored in a model file (env, algorithm config), and an algorithm
// with the stored weights, checking the spaces against `observation_space`/`action_space`.
// `overrides` are the user's `--set key=value` (trusted, unlike the file); `trust` whether the
// user accepted the file's config as a whole (--trust: runtime/io/model_trust.hpp).
Experiment experiment_from_model(const ModelFile& model, const Registry& registry,
                                 const std::vector<std::string>& overrides = {},
                                 const ModelTrust& trust = {}, ModelEnv use = ModelEnv::kRun);
std::unique_ptr<Algorithm> algorithm_from_model(const ModelFile& model,
                                                const Experiment& experiment,
                                                const Registry& registry,
                                                const Space& observation_space,
                                                const Space& action_space);

// The env the model was trained on (make_env of its stored config), with the stored
// normalisation statistics loaded and frozen (SB3: VecNormalize.load + training = False), as
// eval and record need it. `monitor_path` as in make_env. Throws RuntimeFailure when the file
// lacks statistics its config's wrappers need.
EnvPtr make_model_env(const ModelFile& model, const Experiment& experiment,
                      const Registry& registry, const std::string& monitor_path = "");

// What `rlrun eval --model` and `rlrun record --model` need from an untrusted model file:
// phase 1, the experiment and env (statistics frozen) and algorithm built from its config, then
// phase 2 with the budget of model_tensor_budget(), and the weights loaded. Throws
// RuntimeFailure (exit 1) naming the file for anything wrong in it.
struct LoadedModel {
  ModelFile file;
  Experiment experiment;
  EnvPtr env;
  std::unique_ptr<Algorithm> algorithm;
};
// `overrides`, `trust` and `use` as for experiment_from_model; with kSpacesOnly, `env` cannot
// be stepped. `sb3_env_section`: for an SB3 file, env settings from beside it
// (runtime/io/sb3/sb3_model_file.hpp), read as untrusted as the file.
LoadedModel load_model(const std::string& path, const Registry& registry,
                       const std::vector<std::string>& overrides = {}, const ModelTrust& trust = {},
                       ModelEnv use = ModelEnv::kRun,
                       const YAML::Node& sb3_env_section = YAML::Node());

}  // namespace rlrun
