#pragma once
// ScriptedEnv: replays fixed observations and rewards, for wrapper tests with hand-computed
// or numpy-computed expectations. reset k returns resets[k] (cycling), step t returns
// steps[t] and rewards[t] (cycling), and every episode terminates after `episode_length`
// steps. The action space is Box(-2, 2, (act_dim,)); the last action is kept.
#include <span>
#include <vector>

#include "rlrun/env.hpp"

namespace rlrun::testing {

class ScriptedEnv : public Env {
 public:
  ScriptedEnv(std::vector<std::vector<float>> resets, std::vector<std::vector<float>> steps,
              std::vector<double> rewards, int episode_length, int act_dim = 1)
      : resets_(std::move(resets)),
        steps_(std::move(steps)),
        rewards_(std::move(rewards)),
        episode_length_(episode_length),
        obs_space_(Space::box(-100.0f, 100.0f, {static_cast<int>(resets_.front().size())})),
        act_space_(Space::box(-2.0f, 2.0f, {act_dim})),
        last_action_(act_dim, 0.0f) {}

  const Space& observation_space() const override { return obs_space_; }
  const Space& action_space() const override { return act_space_; }
  void reset(std::optional<uint64_t>, std::span<float> obs) override {
    const auto& o = resets_[reset_count_++ % resets_.size()];
    std::copy(o.begin(), o.end(), obs.begin());
    episode_steps_ = 0;
  }
  StepResult step(std::span<const float> action, std::span<float> obs) override {
    std::copy(action.begin(), action.end(), last_action_.begin());
    const size_t t = step_count_++;
    const auto& o = steps_[t % steps_.size()];
    std::copy(o.begin(), o.end(), obs.begin());
    const bool end = ++episode_steps_ >= episode_length_;
    return {rewards_[t % rewards_.size()], end, false};
  }
  const Info& info() const override { return info_; }
  std::string id() const override { return "Scripted-v0"; }

  const std::vector<float>& last_action() const { return last_action_; }

 private:
  std::vector<std::vector<float>> resets_, steps_;
  std::vector<double> rewards_;
  int episode_length_;
  Space obs_space_, act_space_;
  std::vector<float> last_action_;
  size_t reset_count_ = 0, step_count_ = 0;
  int episode_steps_ = 0;
  Info info_;
};

}  // namespace rlrun::testing
