#pragma once
// Frame skipping: each action is repeated `skip` times, the rewards summed, stopping early when
// the episode ends. Two flavours, as the Python stack has them:
//  * FrameSkip (rl_zoo3/wrappers.py FrameSkip, which rl-zoo's CarRacing entry uses): the
//    observation is the last inner step's.
//  * MaxAndSkip (stable_baselines3/common/atari_wrappers.py MaxAndSkipEnv): the observation is
//    the element-wise maximum of the last two inner observations (Atari sprites flicker). As in
//    SB3, the two-frame buffer lives as long as the wrapper: an episode that ends before the
//    second-to-last repeat max-pools with frames of earlier steps (SB3: "the observation on the
//    done=True frame doesn't matter"), and with skip 1 the older slot is never written.
// reset() passes through unchanged in both.
#include <vector>

#include "rlrun/core/config_checks.hpp"
#include "rlrun/env/wrapper.hpp"

namespace rlrun {

class ActionRepeat : public Wrapper {
 public:
  // The policy's action is passed on (the env repeats it); the observations, a frame or the
  // max of the last two, are what the exported policy reads (env/wrapper.hpp).
  bool exports_action_unchanged() const override { return true; }
  // Throws std::invalid_argument when skip < 1, or max_pool on an observation that is not a Box.
  ActionRepeat(EnvPtr inner, int skip, bool max_pool, const char* name);

  StepResult step(std::span<const float> action, std::span<float> obs) override;

 protected:
  void write_own_state(StateWriter& out) const override;
  void read_own_state(const StateReader& in) override;

 private:
  int skip_;
  bool max_pool_;
  std::vector<float> last_two_;  // max_pool: the second-to-last, then the last inner observation
  std::vector<float> scratch_;   // max_pool: an inner observation not kept
};

class FrameSkip : public ActionRepeat {
 public:
  struct Config {
    int skip = 4;
    template <class V>
    void visit(V& v) {
      v("skip", skip, "inner steps per action (rewards summed, last observation)",
        in_range(1, 1000));
    }
  };
  FrameSkip(EnvPtr inner, const Config& config)
      : ActionRepeat(std::move(inner), config.skip, false, "FrameSkip") {}
};

class MaxAndSkip : public ActionRepeat {
 public:
  struct Config {
    int skip = 4;
    template <class V>
    void visit(V& v) {
      v("skip", skip, "inner steps per action (rewards summed, max of the last two observations)",
        in_range(1, 1000));
    }
  };
  MaxAndSkip(EnvPtr inner, const Config& config)
      : ActionRepeat(std::move(inner), config.skip, true, "MaxAndSkip") {}
};

}  // namespace rlrun
