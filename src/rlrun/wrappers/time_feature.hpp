#pragma once
// TimeFeature: sb3_contrib's TimeFeatureWrapper (sb3_contrib/common/wrappers/time_feature.py,
// also rl_zoo3.wrappers.TimeFeatureWrapper), which rl-zoo entries name in `env_wrapper`. The
// observation gets one more float, the remaining fraction of the episode's time,
//     feature = 1 - step / max_steps      (test_mode: always 1.0)
// where `step` counts the episode's steps and max_steps is the stack's time limit (sb3_contrib
// reads env.spec.max_episode_steps), or `max_steps` when the stack has none. The space becomes
// Box(concat(low, 0), concat(high, 1)). Box observations only (rlrun has no goal envs with the
// "observation" key sb3_contrib handles for Dicts).
#include <vector>

#include "rlrun/core/config_checks.hpp"
#include "rlrun/env/wrapper.hpp"

namespace rlrun {

class TimeFeature : public Wrapper {
 public:
  struct Config {
    int max_steps = 1000;    // episode length when the stack has no TimeLimit (sb3_contrib)
    bool test_mode = false;  // feature fixed at 1.0 (sb3_contrib test_mode)
    template <class V>
    void visit(V& v) {
      v("max_steps", max_steps, "episode length used when the env has no time limit", at_least(1));
      v("test_mode", test_mode, "keep the feature at 1.0 (sb3_contrib test_mode)");
    }
  };
  // Throws std::invalid_argument for an observation space that is not a flat Box.
  TimeFeature(EnvPtr inner, const Config& config);

  const Space& observation_space() const override { return space_; }
  void reset(std::optional<uint64_t> seed, std::span<float> obs) override;
  StepResult step(std::span<const float> action, std::span<float> obs) override;

  int max_steps() const { return max_steps_; }

 protected:
  void write_own_state(StateWriter& out) const override {
    out.put_int("time_feature/step", current_step_);
  }
  void read_own_state(const StateReader& in) override {
    current_step_ = static_cast<int>(in.get_count("time_feature/step", INT_MAX));
  }

 private:
  void append_feature(std::span<float> obs);

  Config config_;
  Space space_;
  int max_steps_ = 1000;
  int current_step_ = 0;
  std::vector<float> inner_obs_;
};

}  // namespace rlrun
