#pragma once
// Model files (docs/experiments.md): a zip whose tensors are `<name>.npy` members, so
// `numpy.load("model.zip")` lists the weights, plus `config.yaml` (the resolved experiment) and
// `meta.json` (format version, rlrun version, algorithm, env id, spaces, timesteps).
// Wrappers with model statistics (NormalizeObservation, NormalizeReward) add their running
// mean/var/count as `wrappers/<name>/<field>.npy` (runtime/experiment/env_statistics.hpp);
// make_model_env() (model_loader.hpp) puts them back, frozen, into the env it builds.
// Checkpoints (checkpoints/step_<N>.zip) are model files that also hold the training state for
// `rlrun train --resume` as `training/...` members (core/state_dict.hpp).
// Loading refuses, with the reason, files of another format version, of another algorithm than
// the caller expects, or whose spaces do not match the env they are used with.
//
// Model files are untrusted (docs/security.md): reading one never allocates
// by what the file declares. It happens in two phases —
//  1. read_model_header(): the member list (core/zip_reader.hpp checks), meta.json and
//     config.yaml, each at most kMaxModelTextBytes; no tensor is read;
//  2. read_model_tensors(): the `.npy` members the caller needs, only after their declared
//     sizes together fit a byte budget the CALLER derives from the configuration it built from
//     phase 1 (runtime/io/model_budget.hpp): what a model of that configuration holds, plus slack.
// Members other than meta.json, config.yaml and `*.npy` are skipped unread.
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "rlrun/algos/algorithm.hpp"
#include "rlrun/core/config_node.hpp"
#include "rlrun/core/tensor.hpp"
#include "rlrun/core/zip_archive.hpp"
#include "rlrun/env.hpp"
#include "rlrun/env/env_spaces.hpp"
#include "rlrun/runtime/experiment/experiment.hpp"

namespace rlrun {

inline constexpr int kModelFormatVersion = 1;
inline constexpr const char* kTrainingStatePrefix = "training/";

struct ModelMeta {
  int format_version = kModelFormatVersion;
  std::string rlrun_version;
  std::string algorithm;
  std::string env_id;
  std::string observation_space;  // Space::describe() of the spaces the agent sees
  std::string action_space;
  int64_t num_timesteps = 0;
  // The env's own spaces, under the wrappers ("env_spaces": env/space_json.hpp), so that
  // loading the model for predict or export needs neither the env nor what builds it (a Python
  // worker, a scenario's files). Absent in files written before rlrun recorded them.
  std::optional<EnvSpaces> env_spaces;
};

// Agents a model file may say its env has: a multi-agent env steps each as one env column.
inline constexpr int64_t kMaxModelAgents = 4096;

struct ModelFile {
  std::string path;
  ModelMeta meta;
  std::string config_yaml;
  TensorMap tensors;                  // the algorithm's
  TensorMap wrapper_statistics;       // `wrappers/...` members (see env_statistics.hpp)
  TensorMap training_state;           // `training/...` members (checkpoints only)
  bool holds_training_state = false;  // phase 1: the file has `training/...` members
};

// meta.json and config.yaml: rlrun writes a few KiB.
inline constexpr uint64_t kMaxModelTextBytes = uint64_t{1} << 20;
// What each tensor member costs against a budget beyond its bytes (npy header included in
// `member_bytes`): its name and the bookkeeping of a Tensor in a TensorMap.
inline constexpr uint64_t kTensorOverheadBytes = 256;
inline uint64_t tensor_member_charge(uint64_t name_bytes, uint64_t member_bytes) {
  uint64_t sum = 0;
  if (__builtin_add_overflow(name_bytes, member_bytes, &sum) ||
      __builtin_add_overflow(sum, kTensorOverheadBytes, &sum))
    return UINT64_MAX;
  return sum;
}

// Which tensors read_model_tensors reads: kModel = the algorithm's and `wrappers/...` (eval,
// record, init-from); kCheckpoint = also `training/...` (resume).
enum class ModelParts { kModel, kCheckpoint };

// Writes atomically (temp file + rename). `env` is one copy of the env stack the algorithm
// acts on (its spaces, and its unwrapped env's, are recorded); `env_tensors` are stored beside
// the algorithm's (save_model_statistics() of the training env: normalisation statistics).
void save_model(const std::string& path, const Algorithm& algorithm, const Experiment& experiment,
                Env& env, const TensorMap& env_tensors = {});
// The members save_model writes (for writers into a run directory: core/zip_archive.hpp's
// write_zip_atomic into a DirHandle).
ZipMembers model_members(const Algorithm& algorithm, const Experiment& experiment, Env& env,
                         const TensorMap& env_tensors = {});

// Phase 1 (see the top of this file). Throws RuntimeFailure naming the file and the reason.
ModelFile read_model_header(const std::string& path);
// Phase 2: fills model.tensors, wrapper_statistics (and training_state for kCheckpoint).
// Refuses, before reading any tensor, a file whose selected `.npy` members charge more than
// `budget_bytes` together (tensor_member_charge); then each member's npy header must be valid
// and match its declared size, and its data must decompress to exactly that size. Last, the
// weights and statistics must be finite, and no `wrappers/.../var` or `.../count` negative
// (RuntimeFailure naming the tensor: every command that loads a model refuses it).
void read_model_tensors(ModelFile& model, ModelParts parts, uint64_t budget_bytes);
// Both phases with a fixed budget, for files rlrun just wrote (tests, tools). The commands
// read untrusted files with load_model() / read_checkpoint() (model_budget.hpp) instead.
ModelFile read_model(const std::string& path, uint64_t budget_bytes = uint64_t{1} << 30);

}  // namespace rlrun
