#pragma once
// The names of a multi-agent env's agents (include/rlrun/env.hpp: num_agents() > 1), as
// PettingZoo calls them: its `possible_agents` are strings, and a parallel env's dicts are
// keyed by them (pettingzoo/utils/env.py). TrafficNetwork-v0 names each agent after its
// traffic light (sumo-rl's parallel env uses the light ids too); an env without names gets
// PettingZoo's common "agent_<i>". The Python package's rlrun.parallel_env / rlrun.env
// (python/rlrun/_pettingzoo.py) read them through agent_name_of, under any wrappers.
#include <string>

#include "rlrun/env.hpp"

namespace rlrun {

class AgentNames {
 public:
  virtual ~AgentNames() = default;
  // The name of agent `agent` (0 <= agent < num_agents()); distinct for distinct agents.
  virtual std::string agent_name(int agent) const = 0;
};

inline std::string agent_name_of(Env& env, int agent) {
  if (const auto* names = dynamic_cast<const AgentNames*>(&env.unwrapped()))
    return names->agent_name(agent);
  return "agent_" + std::to_string(agent);
}

}  // namespace rlrun
