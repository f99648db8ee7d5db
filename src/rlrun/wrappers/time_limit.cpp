#include "rlrun/wrappers/time_limit.hpp"

#include <stdexcept>
#include <string>
#include <utility>

namespace rlrun {

TimeLimit::TimeLimit(EnvPtr inner, int max_episode_steps)
    : Wrapper(std::move(inner)), max_episode_steps_(max_episode_steps) {
  if (!inner_) throw std::invalid_argument("TimeLimit: the wrapped env is null");
  if (max_episode_steps <= 0)
    throw std::invalid_argument("TimeLimit: max_episode_steps must be positive, got " +
                                std::to_string(max_episode_steps));
}

void TimeLimit::reset(std::optional<uint64_t> seed, std::span<float> obs) {
  elapsed_steps_ = 0;
  inner_->reset(seed, obs);
}

void TimeLimit::step_agents(std::span<const float> actions, std::span<float> obs,
                            std::span<StepResult> results) {
  inner_->step_agents(actions, obs, results);
  count_agents(results);
}

StepResult TimeLimit::step(std::span<const float> action, std::span<float> obs) {
  return count_step(inner_->step(action, obs));
}

}  // namespace rlrun
