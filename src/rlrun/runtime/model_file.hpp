#pragma once
// Model files (DESIGN.md §5): a zip whose tensors are `<name>.npy` members, so
// `numpy.load("model.zip")` lists the weights, plus `config.yaml` (the resolved experiment) and
// `meta.json` (format version, rlrun version, algorithm, env id, spaces, timesteps).
// Wrappers with model statistics (NormalizeObservation, NormalizeReward) add their running
// mean/var/count as `wrappers/<name>/<field>.npy` (runtime/env_statistics.hpp); make_model_env()
// puts them back, frozen, into the env it builds.
// Checkpoints (checkpoints/step_<N>.zip) are model files that also hold the training state for
// `rlrun train --resume` as `training/...` members (core/state_dict.hpp).
// Loading refuses, with the reason, files of another format version, of another algorithm than
// the caller expects, or whose spaces do not match the env they are used with.
#include <memory>
#include <string>

#include "rlrun/algos/algorithm.hpp"
#include "rlrun/core/config_node.hpp"
#include "rlrun/core/tensor.hpp"
#include "rlrun/runtime/experiment.hpp"

namespace rlrun {

inline constexpr int kModelFormatVersion = 1;
inline constexpr const char* kTrainingStatePrefix = "training/";

struct ModelMeta {
  int format_version = kModelFormatVersion;
  std::string rlrun_version;
  std::string algorithm;
  std::string env_id;
  std::string observation_space;  // Space::describe()
  std::string action_space;
  int64_t num_timesteps = 0;
};

struct ModelFile {
  std::string path;
  ModelMeta meta;
  std::string config_yaml;
  TensorMap tensors;              // the algorithm's
  TensorMap wrapper_statistics;   // `wrappers/...` members (see env_statistics.hpp)
  TensorMap training_state;       // `training/...` members (checkpoints only)
};

// Writes atomically (temp file + rename). `env_tensors` are stored beside the algorithm's
// (save_model_statistics() of the training env: normalisation statistics).
void save_model(const std::string& path, const Algorithm& algorithm, const Experiment& experiment,
                const Space& observation_space, const Space& action_space,
                const TensorMap& env_tensors = {});

// Throws RuntimeFailure naming the file and the reason.
ModelFile read_model(const std::string& path);

// Rebuilds the experiment stored in a model file (env, algorithm config), and an algorithm
// with the stored weights, checking the spaces against `observation_space`/`action_space`.
// `overrides` are the user's `--set key=value` (trusted, unlike the file).
Experiment experiment_from_model(const ModelFile& model, const Registry& registry,
                                 const std::vector<std::string>& overrides = {});
std::unique_ptr<Algorithm> algorithm_from_model(const ModelFile& model, const Experiment& experiment,
                                                const Registry& registry,
                                                const Space& observation_space,
                                                const Space& action_space);

// The env the model was trained on (make_env of its stored config), with the stored
// normalisation statistics loaded and frozen (SB3: VecNormalize.load + training = False), as
// eval and record need it. `monitor_path` as in make_env. Throws RuntimeFailure when the file
// lacks statistics its config's wrappers need.
EnvPtr make_model_env(const ModelFile& model, const Experiment& experiment,
                      const Registry& registry, const std::string& monitor_path = "");

}  // namespace rlrun
