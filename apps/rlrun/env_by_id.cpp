#include "env_by_id.hpp"

#include "rlrun/core/config_node.hpp"
#include "rlrun/core/errors.hpp"
#include "rlrun/runtime/experiment/env_factory.hpp"
#include "rlrun/runtime/experiment/experiment.hpp"

namespace rlrun::cli {

EnvPtr env_by_id(const std::string& id, const Registry& registry,
                 const std::vector<std::string>& overrides) {
  try {
    return make_env(default_env_spec(id, registry, "--env", overrides), registry, "",
                    unix_time_now());
  } catch (const ConfigError& e) {
    throw UsageError(e.what());
  }
}

}  // namespace rlrun::cli
