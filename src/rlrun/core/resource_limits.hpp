#pragma once
// Bounds on what one run may ask of the machine, checked when the config is read, so that a
// setting like `buffer_size: 1e12`, `net_arch: [100000, 100000]` or `n_envs: 100000` is refused
// with its key and the numbers instead of ending in std::bad_alloc or "cannot write monitor
// file" minutes later.
#include <cstdint>
#include <string>

#include "rlrun/core/config_node.hpp"

namespace rlrun {

// This machine's physical memory in bytes (sysconf), or 0 when unknown.
int64_t physical_memory_bytes();

// "" when `bytes` fit the memory rlrun allows one run (the physical memory), else a message
// naming `what` and both numbers, e.g. "the replay buffer needs 48.0 GB, this machine has 23.4 GB".
std::string memory_problem(double bytes, const std::string& what);

// Raises the soft open-file limit up to the hard one when `n_envs` envs need more (each keeps
// its monitor file open, a simulator keeps a socket); fails at `node` when even the hard limit
// is too low, naming `ulimit -n`.
void check_open_files(int n_envs, const ConfigNode& node);

}  // namespace rlrun
