#pragma once
// The action of a Discrete env as an int, after checking it is in the action space (an agent
// or a user script passing 2 to a Discrete(2) env gets an error naming the env, not a wrong
// transition).
#include <span>
#include <stdexcept>
#include <string>

#include "rlrun/space.hpp"

namespace rlrun {

inline int checked_discrete_action(const Space& space, std::span<const float> action,
                                   const std::string& env_id) {
  if (!space.contains(action))
    throw std::invalid_argument(
        env_id + ": action " +
        (action.empty() ? std::string("<empty>") : std::to_string(action[0])) + " is not in " +
        space.describe());
  return static_cast<int>(action[0]);
}

}  // namespace rlrun
