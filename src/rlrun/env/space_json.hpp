#pragma once
// Spaces as JSON, the form Python workers describe their env's spaces in
// (envs/python/worker.py) and model files record them in (meta.json's "env_spaces",
// runtime/io/model_file.hpp):
//   {"kind": "Box", "shape": [2, 3], "low": [...] or one number, "high": ...}   "inf"/"-inf"
//   {"kind": "Discrete", "n": 4, "start": 0}     {"kind": "MultiDiscrete", "nvec": [3, 2]}
//   {"kind": "MultiBinary", "n": 5}              {"kind": "Dict", "spaces": {"key": {...}}}
// Both sources are untrusted, so decoding checks everything before it builds anything: kinds,
// types, every shape entry, sizes that agree, and at most kMaxJsonSpaceFloats floats per sample
// (a space sizes every buffer and network built for it).
#include <cstdint>
#include <nlohmann/json.hpp>

#include "rlrun/space.hpp"

namespace rlrun {

// 2^24 floats (64 MiB) per sample: far beyond any observation rlrun trains on (an 84x84x4
// image is 28 224), small enough that a buffer of one sample is never a memory problem.
inline constexpr int64_t kMaxJsonSpaceFloats = int64_t{1} << 24;

nlohmann::json space_to_json(const Space& space);
// Throws std::invalid_argument saying what is wrong.
Space space_from_json(const nlohmann::json& json);

}  // namespace rlrun
