#pragma once
// What an env looks like from outside without running it: one agent's observation and action
// spaces and the number of agents (rlrun/env.hpp). Parsing an experiment, `rlrun list`, and
// loading a model for predict/export need no more than this, so none of them has to start a
// simulator or a Python worker (env/env_entry.hpp EnvEntry::spaces; model files record it:
// runtime/io/model_file.hpp).
#include "rlrun/env.hpp"
#include "rlrun/space.hpp"

namespace rlrun {

struct EnvSpaces {
  Space observation;
  Space action;
  int num_agents = 1;
  // How the env draws (its size; 0 when it cannot): what AddRenderObservation's space is made
  // of.
  RenderSpec render;
};

inline EnvSpaces spaces_of(const Env& env) {
  return {env.observation_space(), env.action_space(), env.num_agents(), env.render_spec()};
}

}  // namespace rlrun
