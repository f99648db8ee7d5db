#pragma once
// SUMO keeps its simulation in globals (MSNet::getInstance()): one per process, whichever env
// (TrafficSignal-v0 or TrafficNetwork-v0) asks for it. Both entries of the module take this slot.
#include <atomic>
#include <string>

namespace rlrun::libsumo_module {

inline std::atomic<bool> simulation_running{false};

inline const char* kOneSimulation =
    "backend: libsumo runs SUMO inside rlrun, and SUMO allows one simulation per process: use "
    "n_envs: 1 and no separate eval env with libsumo (one env, one rlrun process), or backend: "
    "traci for several envs";

}  // namespace rlrun::libsumo_module
