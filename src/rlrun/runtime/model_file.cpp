#include "rlrun/runtime/model_file.hpp"

#include <nlohmann/json.hpp>

#include "rlrun/core/errors.hpp"
#include "rlrun/core/npy.hpp"
#include "rlrun/core/zip_archive.hpp"
#include "rlrun/runtime/env_factory.hpp"
#include "rlrun/runtime/env_statistics.hpp"

namespace rlrun {

void save_model(const std::string& path, const Algorithm& algorithm, const Experiment& experiment,
                const Space& observation_space, const Space& action_space,
                const TensorMap& env_tensors) {
  TensorMap tensors;
  algorithm.save(tensors);
  ZipMembers members;
  for (const auto& [name, tensor] : tensors) members[name + ".npy"] = encode_npy(tensor);
  for (const auto& [name, tensor] : env_tensors) members[name + ".npy"] = encode_npy(tensor);
  const std::string config = dump_yaml(experiment.resolved);
  members["config.yaml"] = std::vector<uint8_t>(config.begin(), config.end());
  nlohmann::ordered_json meta;
  meta["format_version"] = kModelFormatVersion;
  meta["rlrun_version"] = RLRUN_VERSION;
  meta["algorithm"] = algorithm.id();
  meta["env_id"] = experiment.env.id;
  meta["observation_space"] = observation_space.describe();
  meta["action_space"] = action_space.describe();
  meta["num_timesteps"] = algorithm.num_timesteps();
  const std::string meta_text = meta.dump(2) + "\n";
  members["meta.json"] = std::vector<uint8_t>(meta_text.begin(), meta_text.end());
  write_zip_atomic(path, members);
}

ModelFile read_model(const std::string& path) {
  ZipMembers members = read_zip(path);
  ModelFile model;
  model.path = path;
  const auto meta_it = members.find("meta.json");
  const auto config_it = members.find("config.yaml");
  if (meta_it == members.end() || config_it == members.end())
    throw RuntimeFailure(path + ": not an rlrun model file (no meta.json or config.yaml inside)");
  try {
    const auto meta = nlohmann::json::parse(meta_it->second.begin(), meta_it->second.end());
    model.meta.format_version = meta.at("format_version").get<int>();
    if (model.meta.format_version != kModelFormatVersion)
      throw RuntimeFailure(path + ": model format version " +
                           std::to_string(model.meta.format_version) + " (written by rlrun " +
                           meta.value("rlrun_version", "?") + ") is not supported by rlrun " +
                           RLRUN_VERSION + ", which reads version " +
                           std::to_string(kModelFormatVersion));
    model.meta.rlrun_version = meta.at("rlrun_version").get<std::string>();
    model.meta.algorithm = meta.at("algorithm").get<std::string>();
    model.meta.env_id = meta.at("env_id").get<std::string>();
    model.meta.observation_space = meta.at("observation_space").get<std::string>();
    model.meta.action_space = meta.at("action_space").get<std::string>();
    model.meta.num_timesteps = meta.at("num_timesteps").get<int64_t>();
  } catch (const nlohmann::json::exception& e) {
    throw RuntimeFailure(path + ": meta.json is malformed: " + e.what());
  }
  model.config_yaml.assign(config_it->second.begin(), config_it->second.end());
  for (const auto& [name, bytes] : members) {
    if (name.size() < 4 || name.substr(name.size() - 4) != ".npy") continue;
    const std::string key = name.substr(0, name.size() - 4);
    TensorMap& into = key.rfind(kWrapperStatisticsPrefix, 0) == 0 ? model.wrapper_statistics
                      : key.rfind(kTrainingStatePrefix, 0) == 0  ? model.training_state
                                                                 : model.tensors;
    try {
      into[key] = decode_npy(bytes, path + ":" + name);
    } catch (const std::runtime_error& e) {
      throw RuntimeFailure(e.what());
    }
  }
  return model;
}

Experiment experiment_from_model(const ModelFile& model, const Registry& registry,
                                 const std::vector<std::string>& overrides) {
  // The model's config is data from anyone (docs/security.md): parsed untrusted, so it can
  // name no plugin library, program or output file; the user's --set values can.
  ConfigNode root = ConfigNode::load_string(model.config_yaml, model.path + ":config.yaml",
                                            ConfigTrust::kUntrusted);
  for (const std::string& o : overrides) root.apply_override(o);
  Experiment experiment = parse_experiment(root, registry);
  if (experiment.algo.id != model.meta.algorithm)
    throw RuntimeFailure(model.path + ": meta.json says algorithm " + model.meta.algorithm +
                         " but config.yaml says " + experiment.algo.id);
  return experiment;
}

std::unique_ptr<Algorithm> algorithm_from_model(const ModelFile& model, const Experiment& experiment,
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
  const AlgorithmEntry* entry = registry.find_algorithm(experiment.algo.id);
  if (!entry) throw RuntimeFailure(model.path + ": unknown algorithm " + experiment.algo.id);
  AlgorithmSetup setup{observation_space, action_space, 1, experiment.run.seed};
  std::unique_ptr<Algorithm> algorithm;
  try {
    algorithm = entry->make(experiment.algo.params, setup);
  } catch (const std::invalid_argument& e) {
    throw RuntimeFailure(model.path + ": " + e.what());
  }
  try {
    algorithm->load(model.tensors);
  } catch (const std::runtime_error& e) {
    throw RuntimeFailure(model.path + ": " + e.what());
  }
  return algorithm;
}

EnvPtr make_model_env(const ModelFile& model, const Experiment& experiment,
                      const Registry& registry, const std::string& monitor_path) {
  EnvPtr env = make_env(experiment.env, registry, monitor_path, unix_time_now());
  try {
    load_model_statistics(*env, model.wrapper_statistics, /*training=*/false);
  } catch (const StateMismatch& e) {
    throw RuntimeFailure(model.path + ": the model's env normalises with statistics the file does not hold: " +
                         e.what());
  }
  return env;
}

}  // namespace rlrun
