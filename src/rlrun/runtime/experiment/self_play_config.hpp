#pragma once
// The `self_play:` section of an experiment file, as plain data (run/self_play_callback.hpp
// keeps the pool): snapshots of the learner's policy that two-player game envs with
// `opponent: self_play` sample their opponents from (env/policy_pool.hpp).
#include <cstdint>

#include "rlrun/core/config_checks.hpp"

namespace rlrun {

struct SelfPlayConfig {
  int64_t freq = 0;                 // total env steps between snapshots (0 = no self-play)
  int pool_size = 10;               // snapshots kept, the oldest dropped first
  double latest_probability = 0.5;  // an episode's opponent is the latest snapshot this often
  template <class V>
  void visit(V& v) {
    v("freq", freq,
      "snapshot the learner's policy into the pool every `freq` TOTAL env steps (0 = no "
      "self-play; the first snapshot is the untrained policy at step 0)",
      non_negative());
    v("pool_size", pool_size, "snapshots kept in the pool, the oldest dropped first",
      in_range(1, 1000));
    v("latest_probability", latest_probability,
      "probability that an episode's opponent is the latest snapshot; otherwise one of the "
      "older ones, uniformly",
      unit_interval());
  }
};

}  // namespace rlrun
