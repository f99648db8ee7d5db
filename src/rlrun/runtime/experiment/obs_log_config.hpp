#pragma once
// The `obs_log:` section of an experiment file, as plain data (run/obs_log_callback.hpp
// records the observations).
#include <cstdint>

#include "rlrun/core/config_checks.hpp"

namespace rlrun {

// The `section:` of the experiment file: the course's ObsSaveCallback.
struct ObsLogConfig {
  int64_t freq = 0;  // total env steps between .npy chunks (0 = off)
  int env = 0;       // which training env's observations are logged
  template <class V>
  void visit(V& v) {
    v("freq", freq,
      "save the observations of training env `env` to obs_log/obs_<N>.npy every `freq` TOTAL env "
      "steps (0 = off)",
      non_negative());
    v("env", env, "index of the training env whose observations are logged", non_negative());
  }
};

}  // namespace rlrun
