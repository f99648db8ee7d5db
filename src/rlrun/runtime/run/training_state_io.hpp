#pragma once
// Where each part of a run's training state lives inside a checkpoint (`training/<part>/...`
// members, core/state_dict.hpp), and the parts the trainer itself owns: the callbacks' counters
// and the logger's values not yet written to progress.csv.
#include <memory>
#include <vector>

#include "rlrun/core/logger.hpp"
#include "rlrun/core/state_dict.hpp"
#include "rlrun/runtime/io/model_file.hpp"
#include "rlrun/runtime/run/callback.hpp"

namespace rlrun {

inline constexpr const char* kAlgoState = "algo";
inline constexpr const char* kEnvState = "env";
inline constexpr const char* kCallbackState = "callbacks";
inline constexpr const char* kLoggerState = "logger";
inline constexpr const char* kFileMarks = "files";
inline constexpr const char* kTensorBoardState = "tensorboard";

// Writes the parts under `training/` into a checkpoint's tensors.
class TrainingStateWriter {
 public:
  explicit TrainingStateWriter(TensorMap& tensors) : tensors_(tensors) {}
  StateWriter part(const char* name) const {
    return StateWriter(tensors_, std::string(kTrainingStatePrefix) + name + "/");
  }

 private:
  TensorMap& tensors_;
};

inline StateReader training_state_reader(const ModelFile& checkpoint, const char* part) {
  return StateReader(checkpoint.training_state, std::string(kTrainingStatePrefix) + part + "/");
}

void write_callback_states(StateWriter out,
                           const std::vector<std::unique_ptr<Callback>>& callbacks);
// Throws StateMismatch when the checkpoint was written with other callbacks than `callbacks`.
void read_callback_states(const StateReader& in, std::vector<std::unique_ptr<Callback>>& callbacks);

void write_pending_log(StateWriter out, const LogRow& row);
LogRow read_pending_log(const StateReader& in);

}  // namespace rlrun
