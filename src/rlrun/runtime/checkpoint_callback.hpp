#pragma once
// `checkpoint: {freq, keep}` — SB3's CheckpointCallback counting TOTAL env steps: once `freq`
// more total steps have passed, writes `<run_dir>/checkpoints/step_<N>.zip` atomically (temp
// file + rename) at the next point where training can resume exactly (TrainingHooks::
// at_safe_point: at once for off-policy algorithms, at the end of the rollout's update for
// PPO/A2C), N = total env steps then; then deletes the oldest so that at most `keep` remain
// (keep 0: all, as SB3 does). Checkpoints already in the directory (a resumed run) count.
// A checkpoint is a model file (eval and record read it) plus the training state that
// `rlrun train --resume` continues from.
#include <cstdint>
#include <string>
#include <vector>

#include "rlrun/runtime/callback.hpp"

namespace rlrun {

class CheckpointCallback : public Callback {
 public:
  explicit CheckpointCallback(TrainingContext& context);
  bool on_step(int64_t num_timesteps) override;
  void at_safe_point(int64_t num_timesteps) override;
  void write_state(StateWriter& out) const override;
  void read_state(const StateReader& in) override;

  // `<dir>/step_<N>.zip` files present, oldest (smallest N) first.
  static std::vector<std::string> list_checkpoints(const std::string& dir);

 private:
  TrainingContext& context_;
  const CheckpointConfig& config_;
  std::string dir_;
  int64_t next_;
  bool due_ = false;  // freq steps passed; write at the next safe point
  std::vector<std::string> kept_;  // oldest first
};

}  // namespace rlrun
