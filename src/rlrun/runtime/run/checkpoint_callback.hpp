#pragma once
// `checkpoint: {freq, keep}` — SB3's CheckpointCallback counting TOTAL env steps: once `freq`
// more total steps have passed, writes `<run_dir>/checkpoints/step_<N>.zip` atomically (temp
// file + rename) at the next point where training can resume exactly (TrainingHooks::
// at_safe_point: at once for off-policy algorithms, at the end of the rollout's update for
// PPO/A2C), N = total env steps then; then deletes the oldest so that at most `keep` remain
// (keep 0: all, as SB3 does). Checkpoints already in the directory (a resumed run) count.
// A checkpoint is a model file (eval and record read it) plus the training state that
// `rlrun train --resume` continues from.
// checkpoints/ is held open and never a link (core/dir_handle.hpp): a resumed run directory may
// come from anyone, and keep-N deletes only step_<N>.zip files that are really in it.
#include <cstdint>
#include <string>
#include <vector>

#include "rlrun/core/dir_handle.hpp"
#include "rlrun/runtime/experiment/checkpoint_config.hpp"
#include "rlrun/runtime/run/callback.hpp"

namespace rlrun {

class CheckpointCallback : public Callback {
 public:
  CheckpointCallback(TrainingContext& context, const CheckpointConfig& config);
  bool on_step(int64_t num_timesteps) override;
  void at_safe_point(int64_t num_timesteps) override;
  void write_state(StateWriter& out) const override;
  void read_state(const StateReader& in) override;

  // The names of the step_<N>.zip regular files in `dir` (links and others left out), oldest
  // (smallest N) first.
  static std::vector<std::string> list_checkpoints(const DirHandle& dir);

 private:
  TrainingContext& context_;
  const CheckpointConfig& config_;
  DirHandle dir_;  // <run_dir>/checkpoints
  int64_t next_;
  bool due_ = false;               // freq steps passed; write at the next safe point
  std::vector<std::string> kept_;  // names in dir_, oldest first
};

}  // namespace rlrun
