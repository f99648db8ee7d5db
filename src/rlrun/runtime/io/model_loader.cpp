#include "rlrun/runtime/io/model_loader.hpp"

#include <cstdio>

#include "rlrun/core/errors.hpp"
#include "rlrun/runtime/experiment/env_factory.hpp"
#include "rlrun/runtime/experiment/env_statistics.hpp"
#include "rlrun/runtime/io/model_budget.hpp"
#include "rlrun/runtime/io/sb3/sb3_model_file.hpp"

namespace rlrun {

Experiment experiment_from_model(const ModelFile& model, const Registry& registry,
                                 const std::vector<std::string>& overrides, const ModelTrust& trust,
                                 ModelEnv use) {
  // The model's config is data from anyone (docs/security.md): parsed untrusted, so it can
  // name no plugin library, program or output file; the user's --set values can, and so can
  // the whole file when the user accepts it (--trust), each value printed first.
  ConfigNode root =
      ConfigNode::load_string(model.config_yaml, model.path + ":config.yaml", trust.config_trust());
  root.set_trust_option(trust.option);
  // Where training wrote TensorBoard files: nothing that loads a model writes any, so the
  // run's directory is not the user's to vouch for (it refused every model of a run with
  // --tensorboard-log).
  if (root.is_map() && root.child("run").is_map()) root.yaml()["run"].remove("tensorboard_log");
  for (const std::string& o : overrides) root.apply_override(o);
  ParseOptions options;
  options.recorded_env_spaces = model.meta.env_spaces;
  options.env_not_built = use == ModelEnv::kSpacesOnly && model.meta.env_spaces.has_value();
  Experiment experiment = parse_experiment(root, registry, options);
  if (experiment.algo.id != model.meta.algorithm)
    throw RuntimeFailure(model.path + ": meta.json says algorithm " + model.meta.algorithm +
                         " but config.yaml says " + experiment.algo.id);
  return experiment;
}

namespace {

// An algorithm of the model's configuration with fresh weights.
std::unique_ptr<Algorithm> make_model_algorithm(const ModelFile& model,
                                                const Experiment& experiment,
                                                const Registry& registry,
                                                const Space& observation_space,
                                                const Space& action_space) {
  if (observation_space.describe() != model.meta.observation_space)
    throw RuntimeFailure(model.path + ": the model was trained on observations " +
                         model.meta.observation_space + " but the env has " +
                         observation_space.describe());
  if (action_space.describe() != model.meta.action_space)
    throw RuntimeFailure(model.path + ": the model was trained on actions " +
                         model.meta.action_space + " but the env has " + action_space.describe());
  const AlgorithmSetup setup{observation_space, action_space, 1, experiment.run.seed};
  try {
    return make_algorithm(experiment, registry, setup);
  } catch (const ConfigError& e) {
    throw RuntimeFailure(e.what());  // the file's config, not the user's: exit 1
  }
}

void load_weights(const ModelFile& model, Algorithm& algorithm) {
  try {
    algorithm.load(model.tensors);
  } catch (const std::runtime_error& e) {
    throw RuntimeFailure(model.path + ": " + e.what());
  }
}

// Frozen: SB3's VecNormalize.load + training = False.
void load_frozen_statistics(const ModelFile& model, Env& env) {
  try {
    load_model_statistics(env, model.wrapper_statistics, /*training=*/false);
  } catch (const StateMismatch& e) {
    throw RuntimeFailure(
        model.path +
        ": the model's env normalises with statistics the file does not hold: " + e.what());
  }
}

}  // namespace

std::unique_ptr<Algorithm> algorithm_from_model(const ModelFile& model,
                                                const Experiment& experiment,
                                                const Registry& registry,
                                                const Space& observation_space,
                                                const Space& action_space) {
  std::unique_ptr<Algorithm> algorithm =
      make_model_algorithm(model, experiment, registry, observation_space, action_space);
  load_weights(model, *algorithm);
  return algorithm;
}

EnvPtr make_model_env(const ModelFile& model, const Experiment& experiment,
                      const Registry& registry, const std::string& monitor_path) {
  EnvPtr env = make_env(experiment.env, registry, monitor_path, unix_time_now());
  load_frozen_statistics(model, *env);
  return env;
}

namespace {

// The env stack a model acts on: built (kRun), or over the env's recorded or declared spaces.
EnvPtr model_env(const ModelFile& model, const Experiment& experiment, const Registry& registry,
                 ModelEnv use) {
  if (use == ModelEnv::kSpacesOnly) {
    std::optional<EnvSpaces> spaces = model.meta.env_spaces;
    if (!spaces) spaces = declared_env_spaces(experiment.env, registry);
    if (spaces) return make_spaces_only_env(experiment.env, registry, *spaces);
  }
  return make_env(experiment.env, registry, "", unix_time_now());
}

// The env id the user gave for a model file that does not record one (an SB3 file): the last
// `env.id=ID` override, which the commands' --env ID adds.
std::string overridden_env_id(const std::vector<std::string>& overrides) {
  std::string id;
  for (const std::string& o : overrides)
    if (o.starts_with("env.id=")) id = o.substr(7);
  return id;
}

// An SB3 file is read whole (its weights are in torch's format, not in members of their own).
ModelFile read_sb3_model_for(const std::string& path, const std::vector<std::string>& overrides,
                             const YAML::Node& env_section) {
  const std::string env_id = overridden_env_id(overrides);
  if (env_id.empty())
    throw RuntimeFailure(path +
                         " is an SB3 model file, which does not record the env it was trained "
                         "on: name it with --env ID (for example --env CartPole-v1)");
  return read_sb3_model(path, env_id, env_section);
}

// SB3 files from gym's days record observation bounds Gymnasium has changed since (CartPole's
// velocity bounds were float32's largest value, now infinity; LunarLander's were infinite, now
// finite). SB3's predict does not read observation bounds and rl_zoo3.enjoy plays such files
// without a space check, so a Box of the same shape and dtype is taken as the env's, with a
// note. Image boxes (uint8) and action spaces must match exactly: their bounds matter.
// `policy_spaces`: the spaces the file records its policy saw.
void adopt_observation_bounds(ModelFile& model, const std::optional<EnvSpaces>& policy_spaces,
                              const Space& env_space) {
  if (model.meta.observation_space == env_space.describe() || !env_space.is_box() ||
      env_space.dtype() != BoxDtype::kFloat32 || !policy_spaces)
    return;
  const Space& recorded = policy_spaces->observation;
  if (!recorded.is_box() || recorded.dtype() != BoxDtype::kFloat32 ||
      recorded.shape() != env_space.shape() || model.meta.observation_space != recorded.describe())
    return;
  std::fprintf(stderr,
               "note: %s records observations %s, the env has %s: the same shape and dtype, "
               "played as SB3's predict plays it\n",
               model.path.c_str(), model.meta.observation_space.c_str(),
               env_space.describe().c_str());
  model.meta.observation_space = env_space.describe();
  if (model.meta.env_spaces) model.meta.env_spaces->observation = env_space;
}

// An SB3 file records the spaces its policy saw, which are the env's own only when nothing
// wraps the env: with wrappers (the user's --set env.wrappers, a zoo folder's env_wrapper and
// frame_stack) the env's own spaces are needed under them, which an env of this program
// declares (with how it renders, for AddRenderObservation).
bool sb3_env_is_wrapped(const std::vector<std::string>& overrides, const YAML::Node& env_section) {
  if (env_section.IsMap() && env_section["wrappers"] && env_section["wrappers"].size() > 0)
    return true;
  for (const std::string& o : overrides)
    if (o.starts_with("env.wrappers")) return true;
  return false;
}

LoadedModel load_model_unguarded(const std::string& path, const Registry& registry,
                                 const std::vector<std::string>& overrides, const ModelTrust& trust,
                                 ModelEnv use, const YAML::Node& sb3_env_section) {
  LoadedModel loaded;
  const bool sb3 = is_sb3_model_file(path);
  loaded.file =
      sb3 ? read_sb3_model_for(path, overrides, sb3_env_section) : read_model_header(path);
  const std::optional<EnvSpaces> policy_spaces = loaded.file.meta.env_spaces;
  if (sb3 && sb3_env_is_wrapped(overrides, sb3_env_section) &&
      registry.find_env(loaded.file.meta.env_id))
    loaded.file.meta.env_spaces.reset();
  const ModelFile& model = loaded.file;
  // Without recorded spaces the env must say them, so this program must have it (the deploy
  // library's registry holds no env).
  if (use == ModelEnv::kSpacesOnly && !model.meta.env_spaces &&
      !registry.find_env(model.meta.env_id))
    throw RuntimeFailure(path +
                         ": written by an rlrun that did not record the env's spaces in "
                         "meta.json (env_spaces), and this program does not have " +
                         model.meta.env_id +
                         " to learn them from; `rlrun export`, `rlrun eval` "
                         "and the Python package's rlrun.load read it, and a model trained again "
                         "records them");
  loaded.experiment = experiment_from_model(model, registry, overrides, trust, use);
  // make_model_env's env, before its statistics are read.
  loaded.env = model_env(model, loaded.experiment, registry, use);
  if (sb3) adopt_observation_bounds(loaded.file, policy_spaces, loaded.env->observation_space());
  loaded.algorithm =
      make_model_algorithm(model, loaded.experiment, registry, loaded.env->observation_space(),
                           loaded.env->action_space());
  if (!sb3)
    read_model_tensors(loaded.file, ModelParts::kModel,
                       model_tensor_budget(*loaded.algorithm, *loaded.env));
  load_weights(model, *loaded.algorithm);
  load_frozen_statistics(model, *loaded.env);
  return loaded;
}

}  // namespace

LoadedModel load_model(const std::string& path, const Registry& registry,
                       const std::vector<std::string>& overrides, const ModelTrust& trust,
                       ModelEnv use, const YAML::Node& sb3_env_section) {
  // The config in the file sizes the env and networks built before any tensor is read: a
  // size beyond this machine's memory is the file's problem, said as such.
  try {
    return load_model_unguarded(path, registry, overrides, trust, use, sb3_env_section);
  } catch (const std::bad_alloc&) {
    throw RuntimeFailure(path +
                         ": its config.yaml describes an env or networks larger than this "
                         "machine's memory (std::bad_alloc while building them)");
  }
}

}  // namespace rlrun
