#pragma once
// The `checkpoint:` section of an experiment file, as plain data (run/checkpoint_callback.hpp
// writes the checkpoints).
#include <cstdint>

#include "rlrun/core/config_checks.hpp"

namespace rlrun {

// The `section:` of the experiment file: SB3 CheckpointCallback.
struct CheckpointConfig {
  int64_t freq = 0;  // total env steps between checkpoints (0 = off)
  int keep = 0;      // newest checkpoints kept (0 = all)
  template <class V>
  void visit(V& v) {
    v("freq", freq, "write checkpoints/step_<N>.zip every `freq` TOTAL env steps (0 = never)",
      non_negative());
    v("keep", keep, "keep only the newest `keep` checkpoints (0 = keep all)", non_negative());
  }
};

}  // namespace rlrun
