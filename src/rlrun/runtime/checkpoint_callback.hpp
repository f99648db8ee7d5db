#pragma once
// `checkpoint: {freq, keep}` — SB3's CheckpointCallback counting TOTAL env steps: every `freq`
// total steps writes `<run_dir>/checkpoints/step_<N>.zip` (N = total env steps so far)
// atomically (temp file + rename), then deletes the oldest so that at most `keep` remain
// (keep 0: all, as SB3 does). Checkpoints already in the directory (a resumed run) count.
#include <cstdint>
#include <string>
#include <vector>

#include "rlrun/runtime/callback.hpp"

namespace rlrun {

class CheckpointCallback : public Callback {
 public:
  explicit CheckpointCallback(TrainingContext& context);
  bool on_step(int64_t num_timesteps) override;

  // `<dir>/step_<N>.zip` files present, oldest (smallest N) first.
  static std::vector<std::string> list_checkpoints(const std::string& dir);

 private:
  TrainingContext& context_;
  const CheckpointConfig& config_;
  std::string dir_;
  int64_t next_;
  std::vector<std::string> kept_;  // oldest first
};

}  // namespace rlrun
