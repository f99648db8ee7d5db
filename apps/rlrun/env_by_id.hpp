#pragma once
// An env by id alone, with its registered defaults (TimeLimit, Monitor), as `env: {id: ID}`
// would make it: `record --env ID`, `eval --env ID --policy scripted`. An unknown id is a
// UsageError naming the closest registered one.
#include <string>
#include <vector>

#include "rlrun/env.hpp"
#include "rlrun/runtime/components/registry.hpp"

namespace rlrun::cli {

// `overrides`: `--set env.*=...` values (env.python, env.kwargs.*, env.max_episode_steps).
EnvPtr env_by_id(const std::string& id, const Registry& registry,
                 const std::vector<std::string>& overrides = {});

}  // namespace rlrun::cli
