#pragma once
// One step of every agent of an env, for the code that runs whole episodes (evaluation,
// recording, check-env's random baseline): a single-agent env steps as usual; a multi-agent env
// (include/rlrun/env.hpp) steps all its agents, `actions` and `obs` agent-major, and the
// result is the episode's view of the step: the rewards summed (PettingZoo's total reward, as
// Monitor counts it) and the episode over when any agent's is (they end together).
#include <span>
#include <vector>

#include "rlrun/env.hpp"

namespace rlrun {

inline StepResult step_all_agents(Env& env, std::span<const float> actions, std::span<float> obs,
                                  std::vector<StepResult>& scratch) {
  const int agents = env.num_agents();
  if (agents == 1) return env.step(actions, obs);
  scratch.resize(static_cast<size_t>(agents));
  env.step_agents(actions, obs, scratch);
  StepResult total;
  for (const StepResult& r : scratch) {
    total.reward += r.reward;
    total.terminated = total.terminated || r.terminated;
    total.truncated = total.truncated || r.truncated;
  }
  return total;
}

}  // namespace rlrun
