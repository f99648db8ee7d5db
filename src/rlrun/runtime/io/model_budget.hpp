#pragma once
// How many bytes of tensors an untrusted model file or checkpoint may make rlrun read
// (model_file.hpp, phase 2). The bound never comes from the file: it is what an algorithm and
// env built from the (validated) configuration hold themselves, measured on freshly built
// ones, plus slack — so a file can make rlrun allocate about as much as the model it claims to
// be, and no more. docs/security.md states the bounds; tests/runtime/test_model_budget.cpp
// checks that real files of every algorithm fit them.
#include <cstdint>
#include <string>

#include "rlrun/algos/algorithm.hpp"
#include "rlrun/env.hpp"
#include "rlrun/runtime/experiment/experiment.hpp"
#include "rlrun/runtime/io/model_file.hpp"

namespace rlrun {

// Slack of a model file's budget: tensors of a newer minor version, rounding.
inline constexpr uint64_t kModelSlackBytes = uint64_t{1} << 20;
// Slack of a checkpoint's training state: the log marks and pending log row (text stored as one
// int64 per byte), episode statistics, callback state.
inline constexpr uint64_t kCheckpointSlackBytes = uint64_t{16} << 20;
inline constexpr uint64_t kCheckpointSlackPerEnvBytes = uint64_t{64} << 10;

// The charge (tensor_member_charge) of `tensors` as `<prefix><key>.npy` members.
uint64_t tensor_map_charge(const TensorMap& tensors, const std::string& prefix = "");

// eval, record, init-from (ModelParts::kModel): the charge of `algorithm`'s save() and of the
// statistics of `env`'s wrappers, plus 16 bytes per observation element (a NormalizeObservation
// mean and var the file may hold and `env` lacks: init-from into a run without one), plus
// kModelSlackBytes. `algorithm` must be built from the same configuration as the file's.
uint64_t model_tensor_budget(const Algorithm& algorithm, Env& env);

// ReplayBuffer::write_state (algos/common/replay_buffer.cpp) writes only the filled transitions,
// so a fresh buffer's state has 0 columns: the bytes its tensors gain when the buffer is full
// (for each `.../capacity` entry, every sibling tensor with a zero extent grown to capacity).
uint64_t replay_buffer_growth(const TensorMap& fresh_state);

// resume (ModelParts::kCheckpoint): a probe env (experiment.env, n_envs copies, no monitor
// files) and algorithm are built and measured: the model budget above, plus — when the env can
// save its state — the charge of the fresh algorithm's save_training_state() and of the env
// state, the replay buffer full (replay_buffer_growth), obs_log's unsaved rows
// ((obs_log.freq / n_envs + 2) x obs_dim float32), kCheckpointSlackPerEnvBytes per env and
// kCheckpointSlackBytes.
uint64_t checkpoint_tensor_budget(const Experiment& experiment, const Registry& registry);

// Phase 1, then phase 2 with checkpoint_tensor_budget() (skipped, leaving the tensors empty,
// when the file holds no training state: the trainer refuses it). Throws RuntimeFailure.
ModelFile read_checkpoint(const std::string& path, const Experiment& experiment,
                          const Registry& registry);

}  // namespace rlrun
