#pragma once
// The policy of a loaded model file as a PolicyGraph (nn/policy_graph.hpp): the env's own
// observation in, the env's own action out, exactly the steps `rlrun eval --deterministic`
// takes between them: the observation wrappers of the model's env (normalisation with the
// frozen statistics, one-hot encodings), the algorithm's encoding, networks and mode, then the
// action wrappers (RescaleAction, ClipAction, DiscreteAsBox) down to the env.
#include <string>

#include "rlrun/nn/policy_graph.hpp"
#include "rlrun/runtime/io/model_loader.hpp"

namespace rlrun {

// Inputs: one per key of a Dict observation (named by the key, in the space's order), else
// one named "obs" — of the env's observation, or of the outermost wrapper that renders or keeps
// frames but passes actions on (AddRenderObservation, FrameStack, MaxAndSkip: the graph then
// starts at what the policy reads; metadata "observation_input" says so). Throws ExportError
// for a multi-agent env, a wrapper that keeps state and changes actions or has no export
// (TimeFeature), or an algorithm without export.
PolicyGraph build_model_graph(const LoadedModel& model, bool with_value);

}  // namespace rlrun
