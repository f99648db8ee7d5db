#pragma once
// check_env: a conformance check in the spirit of gymnasium/utils/env_checker.py, run on
// every registered env. It returns a list of problems (empty = the env passes):
//   * spaces are usable (non-empty, Box low <= high, a Dict's keys too);
//   * every observation from reset() and step() lies in observation_space (integer values of
//     Discrete / MultiDiscrete entries, 0/1 bits; a report names the Dict key outside);
//   * reset(seed) is deterministic, reset() after it continues deterministically, and two
//     different seeds lead to different resets whenever the reset is random at all;
//   * the same seed and the same actions give the same trajectory (obs, reward, flags, info);
//   * rewards are finite;
//   * reset() after terminated/truncated starts a valid new episode.
// Exceptions thrown by the env are reported as problems, not rethrown.
#include <cstdint>
#include <string>
#include <vector>

#include "rlrun/env.hpp"

namespace rlrun {

std::vector<std::string> check_env(Env& env, uint64_t seed = 0, int steps = 200);

}  // namespace rlrun
