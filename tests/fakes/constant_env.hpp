#pragma once
// A one-dimensional env for unit tests: observation always `value`, reward 1 per step, and
// the episode ends after every `episode_length` steps, by termination or by truncation.
#include "rlrun/env.hpp"

namespace rlrun::fakes {

class ConstantEnv : public Env {
 public:
  ConstantEnv(bool truncate, int episode_length, float value = 0.5f)
      : truncate_(truncate), episode_length_(episode_length), value_(value) {}
  const Space& observation_space() const override { return obs_space_; }
  const Space& action_space() const override { return act_space_; }
  void reset(std::optional<uint64_t>, std::span<float> obs) override {
    steps_ = 0;
    obs[0] = value_;
  }
  StepResult step(std::span<const float>, std::span<float> obs) override {
    obs[0] = value_;
    const bool end = ++steps_ >= episode_length_;
    return {1.0, end && !truncate_, end && truncate_};
  }
  const Info& info() const override { return info_; }
  std::string id() const override { return "Constant-v0"; }

 private:
  bool truncate_;
  int episode_length_;
  float value_;
  int steps_ = 0;
  Space obs_space_ = Space::box(-1.0f, 1.0f, {1});
  Space act_space_ = Space::discrete(2);
  Info info_;
};

}  // namespace rlrun::fakes
