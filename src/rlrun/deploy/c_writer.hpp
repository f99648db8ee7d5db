#pragma once
// A PolicyGraph as dependency-free C99 (`rlrun export --format c`): policy.h declares
//     void policy_act(const float *obs, float *action);
// (a recurrent policy's: `void policy_act(const float *obs, float *state, float *action);`, the
// state POLICY_STATE_DIM floats updated in place, zeros at an episode's start)
// and policy.c defines it with the weights as `static const float` arrays. One observation per
// call (the flat observation: a Dict's keys concatenated in key order, as the ONNX inputs are
// listed), no dynamic memory, no libm beyond tanhf, expf and erfcf; every intermediate is a fixed-size
// local array. For microcontrollers and plain C programs (RLtools ships the same idea).
// The arithmetic is the graph's, in float: dense layers sum in input order, ELU is
// expf(x) - 1, the one-hot rounds half away from zero (observation values are integers).
// Text from the model file (metadata, Dict keys) goes into policy.h's comment only, through
// c_comment_text (deploy/c_comment_text.hpp); every number is a C literal (HUGE_VALF for an
// infinite bound): a NaN or other infinite number is refused (deploy/graph_numbers.hpp).
#include <string>

#include "rlrun/nn/policy_graph.hpp"

namespace rlrun {

struct CSource {
  std::string header;  // policy.h
  std::string source;  // policy.c (includes "policy.h")
};

// Throws ExportError for a graph without an action or with a number C cannot hold.
CSource c_policy_source(const PolicyGraph& graph);

}  // namespace rlrun
