#pragma once
// A PolicyGraph as dependency-free C99 (`rlrun export --format c`): policy.h declares
//     void policy_act(const float *obs, float *action);
// and policy.c defines it with the weights as `static const float` arrays. One observation per
// call (the flat observation: a Dict's keys concatenated in key order, as the ONNX inputs are
// listed), no dynamic memory, no libm beyond tanhf and expf; every intermediate is a fixed-size
// local array. For microcontrollers and plain C programs (RLtools ships the same idea).
// The arithmetic is the graph's, in float: dense layers sum in input order, ELU is
// expf(x) - 1, the one-hot rounds half away from zero (observation values are integers).
#include <string>

#include "rlrun/nn/policy_graph.hpp"

namespace rlrun {

struct CSource {
  std::string header;  // policy.h
  std::string source;  // policy.c (includes "policy.h")
};

CSource c_policy_source(const PolicyGraph& graph);

}  // namespace rlrun
