#pragma once
// Live env objects: `rlrun.PPO("MlpPolicy", env)` from the `rlrun` Python package with a
// gymnasium.Env object built in the user's interpreter (SB3's usage), stepped where it lives.
// The package numbers the object and trains on the env id `python-object:<number>`; each env
// built from that id asks the connector for a socket whose other end a thread of the package
// serves with worker.py's loop over that very object (python_env.hpp's protocol, so its spaces,
// checks, info and errors are those of any Python env). Only the process that holds the
// object can connect: in the `rlrun` program, or for an unknown number, the id is an error.
#include <cstdint>
#include <functional>

namespace rlrun {

// Returns a connected socket's fd for object `number`; throws RuntimeFailure with the reason
// when there is none (never a negative fd).
using LiveEnvConnector = std::function<int(int64_t number)>;

// Set once by the Python package's extension when it is imported; empty elsewhere.
void set_live_env_connector(LiveEnvConnector connector);
const LiveEnvConnector& live_env_connector();

}  // namespace rlrun
