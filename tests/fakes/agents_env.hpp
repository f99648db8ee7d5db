#pragma once
// AgentsEnv: a multi-agent env (include/rlrun/env.hpp's PettingZoo-style shape) for VecEnv,
// wrapper and training tests. Each of `agents` agents sees its own target in {0, 1} (one-hot,
// drawn at reset and after every step) and gets reward 1 when its Discrete(2) action equals
// the target: a shared policy learns it quickly. The episode ends for all agents after
// `episode_length` steps (terminated), or never when it is 0 (a TimeLimit ends it).
#include <cstdint>
#include <optional>
#include <span>
#include <stdexcept>
#include <vector>

#include "rlrun/env_base.hpp"

namespace rlrun::testing {

class AgentsEnv : public EnvBase {
 public:
  AgentsEnv(int agents, int episode_length) : agents_(agents), episode_length_(episode_length) {
    observation_space_ = Space::box(0.0f, 1.0f, {2});
    action_space_ = Space::discrete(2);
    id_ = "Agents-v0";
    targets_.resize(static_cast<size_t>(agents));
  }

  int num_agents() const override { return agents_; }

  void reset(std::optional<uint64_t> seed, std::span<float> obs) override {
    seeding_.on_reset(seed);
    steps_ = 0;
    draw(obs);
  }
  StepResult step(std::span<const float>, std::span<float>) override {
    throw std::logic_error("AgentsEnv has several agents: use step_agents");
  }
  void step_agents(std::span<const float> actions, std::span<float> obs,
                   std::span<StepResult> results) override {
    ++steps_;
    const bool ended = episode_length_ > 0 && steps_ >= episode_length_;
    for (int a = 0; a < agents_; ++a)
      results[a] = {actions[a] == static_cast<float>(targets_[a]) ? 1.0 : 0.0, ended, false};
    draw(obs);
  }

 private:
  void draw(std::span<float> obs) {
    for (int a = 0; a < agents_; ++a) {
      targets_[a] = static_cast<int>(seeding_.rng().below(2));
      obs[2 * a] = targets_[a] == 0 ? 1.0f : 0.0f;
      obs[2 * a + 1] = targets_[a] == 1 ? 1.0f : 0.0f;
    }
  }

  int agents_;
  int episode_length_;
  int steps_ = 0;
  std::vector<int> targets_;
};

}  // namespace rlrun::testing
