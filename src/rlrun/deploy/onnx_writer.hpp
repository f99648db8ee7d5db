#pragma once
// A PolicyGraph as an ONNX model (onnx/onnx.proto, IR version 7, default-domain opset 13),
// written with rlrun's own protobuf encoder (core/protobuf_writer.hpp): float32 inputs
// [batch, width] with a symbolic batch dimension, outputs "action" [batch, action floats] and,
// when the graph has one, "value"; a recurrent graph adds the input "state_in" and the output
// "state_out" [batch, state floats]; the graph's metadata as the model's metadata_props
// (through printable_utf8, core/utf8_text.hpp: protobuf strings must be UTF-8, and the metadata
// comes from the model file). A NaN, or an infinite number other than a bound, is refused
// (deploy/graph_numbers.hpp), as are Dict keys that cannot be ONNX input names.
//
// Each graph node becomes standard operators: Dense -> Gemm (transB), activations -> Tanh /
// Relu / Elu / LeakyRelu (torch's alpha 1 and 0.01) / GELU as Mul, Erf, Add, Mul (x (1 +
// erf(x / sqrt(2))) / 2; opset 13 has no Gelu), Affine -> Add, Mul, Add, Clamp -> Max,
// Min (per-column bounds, which Clip cannot take), OneHot -> Round, Sub, Equal, Cast,
// ArgMax -> ArgMax (first maximum), Cast, Positive -> Greater, Cast, LstmCell -> Add, Slice,
// Sigmoid, Tanh, Mul, Add, Concat, Slice and Concat as themselves. Discrete actions come out as floats holding the index, as rlrun's own.
#include <string>

#include "rlrun/nn/policy_graph.hpp"

namespace rlrun {

inline constexpr int kOnnxIrVersion = 7;
inline constexpr int kOnnxOpset = 13;

// The serialised ModelProto.
std::string onnx_model_bytes(const PolicyGraph& graph);

}  // namespace rlrun
