#pragma once
// CounterEnv: a tiny deterministic env for VecEnv and checker tests. The observation is
// {start + steps since reset}, where start is the reset seed (or continues from the last
// start + 100 when reset without one), the reward is the action, and the episode terminates
// after `episode_length` steps. Info key "is_success" is 1 on the terminating step, 0 on the
// others and absent after reset(), so tests can tell a step's info from a reset's.
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <utility>

#include "rlrun/env.hpp"

namespace rlrun::testing {

class CounterEnv : public Env {
 public:
  explicit CounterEnv(int episode_length, Space observation_space = Space::box(-1e9f, 1e9f, {1}))
      : episode_length_(episode_length), observation_space_(std::move(observation_space)) {
    is_success_ = info_.add_key("is_success");
  }

  const Space& observation_space() const override { return observation_space_; }
  const Space& action_space() const override { return action_space_; }

  void reset(std::optional<uint64_t> seed, std::span<float> obs) override {
    start_ = seed ? static_cast<float>(*seed) : start_ + 100.0f;
    steps_ = 0;
    ++resets_;
    info_.clear();
    obs[0] = start_;
  }

  StepResult step(std::span<const float> action, std::span<float> obs) override {
    ++steps_;
    info_.clear();
    const bool terminated = steps_ >= episode_length_;
    info_.set(is_success_, terminated ? 1.0 : 0.0);
    obs[0] = start_ + static_cast<float>(steps_);
    return {static_cast<double>(action[0]), terminated, false};
  }

  const Info& info() const override { return info_; }
  std::string id() const override { return "Counter-v0"; }

  int resets() const { return resets_; }

 private:
  int episode_length_;
  Space observation_space_;
  Space action_space_ = Space::box(-10.0f, 10.0f, {1});
  Info info_;
  int is_success_ = -1;
  float start_ = 0.0f;
  int steps_ = 0;
  int resets_ = 0;
};

}  // namespace rlrun::testing
