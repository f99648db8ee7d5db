#include "rlrun/envs/python/python_live_env.hpp"

namespace rlrun {

namespace live_env_detail {
LiveEnvConnector& slot() {
  static LiveEnvConnector connector;
  return connector;
}
}  // namespace live_env_detail

void set_live_env_connector(LiveEnvConnector connector) {
  live_env_detail::slot() = std::move(connector);
}

const LiveEnvConnector& live_env_connector() { return live_env_detail::slot(); }

}  // namespace rlrun
