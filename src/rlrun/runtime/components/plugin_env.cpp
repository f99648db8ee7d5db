#include "rlrun/runtime/components/plugin_env.hpp"

#include <stdexcept>

namespace rlrun {

namespace {

EnvPtr checked(EnvPtr env, const std::string& id) {
  if (!env) throw std::invalid_argument(id + ": the plugin returned no env");
  if (env->observation_space().flat_dim() <= 0)
    throw std::invalid_argument(id + "'s observation_space is not a valid space: " +
                                env->observation_space().describe() + " has no elements");
  if (env->action_space().flat_dim() <= 0)
    throw std::invalid_argument(id + "'s action_space is not a valid space: " +
                                env->action_space().describe() + " has no elements");
  return env;
}

}  // namespace

PluginEnv::PluginEnv(EnvPtr env, std::string id)
    : Wrapper(checked(std::move(env), id)), id_(std::move(id)) {}

}  // namespace rlrun
