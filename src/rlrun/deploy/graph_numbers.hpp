#pragma once
// The numbers of a policy graph, checked before a writer emits them (deploy/c_writer.hpp,
// deploy/onnx_writer.hpp). A NaN or infinite weight has no C99 literal (`nanf` is not C) and
// makes every action NaN; model files with one are refused when read
// (runtime/io/model_file.hpp), but finite float64 statistics can still overflow float32 on the
// way into the graph (a mean of 1e300). Only bounds may be infinite: a Clamp's low and high
// (an unbounded observation or action space).
#include "rlrun/nn/policy_graph.hpp"

namespace rlrun {

// Throws ExportError naming the node and the parameter ("dense_3 (Dense weight) holds nan at
// row 1, column 0") for the first number that is NaN, or infinite where a bound is not.
void check_graph_numbers(const PolicyGraph& graph);

}  // namespace rlrun
