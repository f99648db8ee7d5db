#pragma once
// A trained policy as a small dataflow graph: what `rlrun eval` does between the env's
// observation and the env's action, deterministically, written out as plain operations on
// [batch, width] float tensors. One graph feeds every way a policy leaves rlrun: the ONNX file
// (deploy/onnx_writer.hpp), the C source, and the embeddable rlrun::Policy. Each part of the
// path adds its own nodes: the wrappers of the model's env (observation transforms on the way
// up, action transforms on the way down; Wrapper::export_observation / export_action), the
// algorithm's networks and the distribution's mode (Algorithm::export_policy).
//
// Nodes are in SSA form (ONNX's too): each node reads named tensors and writes one new named
// tensor; the graph is topologically ordered by construction (a node may only read names that
// exist). Every tensor is float32 with a batch dimension and a fixed width; discrete actions are
// floats holding the index (as rlrun's actions are).
//
// A recurrent policy (RecurrentPPO's LSTM) has a state: one more input, "state_in", and one more
// output, "state_out", of the same width. A caller feeds each step's state_out back as the next
// step's state_in, and zeros where an episode starts (what sb3-contrib's predict does with
// episode_start).
#include <Eigen/Core>
#include <map>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

#include "rlrun/nn/activation.hpp"
#include "rlrun/nn/conv2d.hpp"

namespace rlrun {

class Lstm;
class Mlp;
class NatureCnn;

// A model that cannot be exported as it is (a stateful wrapper, an algorithm without export).
class ExportError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

enum class GraphOp {
  kConcat,      // inputs side by side (axis 1)
  kSlice,       // columns [begin, begin + width) of one input
  kDense,       // x W^T + b (weight: width x input width, torch's Linear layout)
  kActivation,  // tanh / relu / elu / leaky_relu / gelu, elementwise
  kAffine,      // (x + c) * a + b, per column (c, a, b: width), in that order: the
                //   normalisation (x - mean) / std and the unscaling low + (a + 1) range / 2
                //   round as rlrun's own code does
  kClamp,       // min(max(x, a), b), per column (bounds may be +-inf)
  kOneHot,      // one column holding an integer value v -> width columns, 1 where
                //   round(v) - start == k (round half to even, ONNX's Round)
  kArgMax,      // index of the first largest entry, as one float column
  kPositive,    // 1 where x > 0, else 0 (a Bernoulli's mode)
  kLstmCell,    // one step of one torch.nn.LSTM layer from three inputs: the input's gates
                //   W_ih x + b_ih + b_hh (4H), the hidden state's W_hh h (4H) and c (H); their
                //   sum's rows i, f, g, o (torch's order) give c' = sigmoid(f) c +
                //   sigmoid(i) tanh(g) and h' = sigmoid(o) tanh(c'); the output is h' then c'
                //   (2H), as nn/lstm.cpp computes them
  kConv2d,      // torch.nn.Conv2d without padding (SB3's NatureCNN's): the input one image of
                //   conv.in_channels x in_height x in_width, channels-last (HWC) or -first (CHW)
                //   as conv.channels_last says; weight out_channels x (C * k * k) in torch's
                //   (c, i, j) order, b the bias; the output channels-first, flattened as torch
                //   flattens it, (o, y, x)
};

struct GraphNode {
  GraphOp op = GraphOp::kConcat;
  std::vector<std::string> inputs;
  std::string output;
  int width = 0;            // columns of the output
  Eigen::MatrixXf weight;   // kDense
  Eigen::VectorXf a, b, c;  // kDense: b = bias; kAffine: see above; kClamp: a low, b high
  Activation activation = Activation::kTanh;  // kActivation
  int begin = 0;                              // kSlice
  float start = 0.0f;                         // kOneHot: the value of column 0
  Conv2dShape conv;                           // kConv2d
};

struct GraphInput {
  std::string name;
  int width = 0;
};

class PolicyGraph {
 public:
  // The observation's inputs: one per Dict key (in the space's order), else one named "obs".
  void add_input(const std::string& name, int width);
  const std::vector<GraphInput>& inputs() const { return inputs_; }
  // The recurrent state's input (kStateInput, `width` floats per batch row; added once, after
  // the observation's inputs) and the tensor that is the next step's state (same width).
  static constexpr const char* kStateInput = "state_in";
  static constexpr const char* kStateOutput = "state_out";
  std::string add_state_input(int width);
  void set_state_output(const std::string& name);
  // Floats of the recurrent state (0: the policy has none).
  int state_width() const { return state_width_; }
  const std::string& state_output() const { return state_output_; }
  // Floats of one whole observation: the inputs' widths together (a Dict's keys in order).
  int observation_width() const { return observation_width_; }
  const std::vector<GraphNode>& nodes() const { return nodes_; }
  // Width of a named tensor (an input or a node's output); throws std::out_of_range.
  int width(const std::string& name) const;

  // Builders: each appends one node with a fresh name (prefix + number) and returns the name.
  // Throw std::invalid_argument for inputs of the wrong width.
  std::string concat(const std::vector<std::string>& inputs);
  std::string slice(const std::string& input, int begin, int width);
  std::string dense(const std::string& input, const Eigen::MatrixXf& weight,
                    const Eigen::VectorXf& bias);
  std::string activation(const std::string& input, Activation activation);
  std::string affine(const std::string& input, const Eigen::VectorXf& pre_shift,
                     const Eigen::VectorXf& scale, const Eigen::VectorXf& post_shift);
  std::string clamp(const std::string& input, const Eigen::VectorXf& low,
                    const Eigen::VectorXf& high);
  std::string one_hot(const std::string& input, float start, int depth);
  std::string argmax(const std::string& input);
  std::string positive(const std::string& input);
  // An Mlp's layers: Dense + activation per hidden layer, then the output layer (no
  // activation).
  std::string mlp(const std::string& input, const Mlp& net);
  // One step of a (stacked) LSTM from `state`, a tensor of net.state_size() floats laid out as
  // rlrun's recurrent states are (every layer's h, then every layer's c): the last layer's h
  // and the next state in the same layout.
  struct LstmStep {
    std::string output, next_state;
  };
  LstmStep lstm(const std::string& input, const Lstm& net, const std::string& state);
  std::string lstm_cell(const std::string& input_gates, const std::string& hidden_gates,
                        const std::string& cell);
  std::string conv2d(const std::string& input, const Conv2dShape& shape,
                     const Eigen::MatrixXf& weight, const Eigen::VectorXf& bias);
  // SB3's NatureCNN from its torch tensors: the image divided by 255 (normalize_images), three
  // Conv2d + ReLU, the Linear layer + ReLU; the input the image in the CNN's layout.
  std::string nature_cnn(const std::string& input, const NatureCnn& cnn);

  // The graph's results: the action (required) and, for --with-value, the critic's output.
  void set_action(const std::string& name) { action_ = name; }
  void set_value(const std::string& name) { value_ = name; }
  const std::string& action() const { return action_; }
  const std::string& value() const { return value_; }

  // Free-form key/value metadata written into exported files (env id, algorithm, spaces...).
  std::map<std::string, std::string> metadata;

 private:
  std::string add(GraphNode node, const char* prefix);
  std::vector<GraphInput> inputs_;
  int observation_width_ = 0;
  int state_width_ = 0;
  std::string state_output_;
  std::vector<GraphNode> nodes_;
  std::map<std::string, int> widths_;
  std::string action_, value_;
};

// A tensor's value for a batch: width x batch floats, a column per observation, each column
// `stride` floats after the previous (a run of rows of a larger matrix, or a matrix of its own).
using GraphBlock = Eigen::Map<Eigen::MatrixXf, 0, Eigen::OuterStride<>>;
using ConstGraphBlock = Eigen::Map<const Eigen::MatrixXf, 0, Eigen::OuterStride<>>;

// One node's output from its inputs' values (inputs[k] for node.inputs[k]): the semantics
// listed at GraphOp. The one implementation of them, shared by evaluate_graph and
// rlrun::Policy; no allocation.
void run_node(const GraphNode& node, std::span<const ConstGraphBlock> inputs, GraphBlock out);

// Runs the graph: inputs[i] is inputs()[i].width x batch (a column per observation, as rlrun's
// matrices), then, for a recurrent graph, the state (state_width() x batch); returns every
// tensor's value by name, each width x batch. For tests and the
// reference path; the library's fast path is rlrun::Policy.
std::map<std::string, Eigen::MatrixXf> evaluate_graph(const PolicyGraph& graph,
                                                      const std::vector<Eigen::MatrixXf>& inputs);

}  // namespace rlrun
