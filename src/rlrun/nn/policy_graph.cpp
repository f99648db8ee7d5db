#include "rlrun/nn/policy_graph.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "rlrun/nn/lstm.hpp"
#include "rlrun/nn/mlp.hpp"
#include "rlrun/nn/nature_cnn.hpp"

namespace rlrun {

void PolicyGraph::add_input(const std::string& name, int width) {
  if (width < 1) throw std::invalid_argument("graph input '" + name + "' has no columns");
  if (widths_.count(name)) throw std::invalid_argument("graph input '" + name + "' twice");
  inputs_.push_back({name, width});
  observation_width_ += width;
  widths_[name] = width;
}

std::string PolicyGraph::add_state_input(int width) {
  if (width < 1 || state_width_ > 0)
    throw std::invalid_argument("graph state input: one, with columns");
  if (widths_.count(kStateInput))
    throw ExportError(std::string("a Dict observation key named '") + kStateInput +
                      "' would clash with the recurrent state's input of that name");
  state_width_ = width;
  widths_[kStateInput] = width;
  return kStateInput;
}

void PolicyGraph::set_state_output(const std::string& name) {
  if (state_width_ == 0 || width(name) != state_width_)
    throw std::invalid_argument("the state output '" + name + "' does not fit the state input");
  state_output_ = name;
}

int PolicyGraph::width(const std::string& name) const {
  const auto it = widths_.find(name);
  if (it == widths_.end()) throw std::out_of_range("graph has no tensor '" + name + "'");
  return it->second;
}

std::string PolicyGraph::add(GraphNode node, const char* prefix) {
  for (const std::string& in : node.inputs) width(in);  // every input exists
  node.output = std::string(prefix) + "_" + std::to_string(nodes_.size());
  // A Dict key may be spelled like a node ("dense_3"): the node's name moves aside.
  while (widths_.count(node.output)) node.output += "_";
  widths_[node.output] = node.width;
  nodes_.push_back(std::move(node));
  return nodes_.back().output;
}

std::string PolicyGraph::concat(const std::vector<std::string>& inputs) {
  if (inputs.size() == 1) return inputs.front();
  GraphNode n;
  n.op = GraphOp::kConcat;
  n.inputs = inputs;
  for (const std::string& in : inputs) n.width += width(in);
  return add(std::move(n), "concat");
}

std::string PolicyGraph::slice(const std::string& input, int begin, int w) {
  if (begin < 0 || w < 1 || begin + w > width(input))
    throw std::invalid_argument("slice outside '" + input + "'");
  if (begin == 0 && w == width(input)) return input;
  GraphNode n;
  n.op = GraphOp::kSlice;
  n.inputs = {input};
  n.begin = begin;
  n.width = w;
  return add(std::move(n), "slice");
}

std::string PolicyGraph::dense(const std::string& input, const Eigen::MatrixXf& weight,
                               const Eigen::VectorXf& bias) {
  if (weight.cols() != width(input) || bias.size() != weight.rows())
    throw std::invalid_argument("dense layer does not fit '" + input + "'");
  GraphNode n;
  n.op = GraphOp::kDense;
  n.inputs = {input};
  n.weight = weight;
  n.b = bias;
  n.width = static_cast<int>(weight.rows());
  return add(std::move(n), "dense");
}

std::string PolicyGraph::activation(const std::string& input, Activation act) {
  GraphNode n;
  n.op = GraphOp::kActivation;
  n.inputs = {input};
  n.activation = act;
  n.width = width(input);
  return add(std::move(n), std::string(activation_name(act)).c_str());
}

std::string PolicyGraph::affine(const std::string& input, const Eigen::VectorXf& pre_shift,
                                const Eigen::VectorXf& scale, const Eigen::VectorXf& post_shift) {
  if (pre_shift.size() != width(input) || scale.size() != width(input) ||
      post_shift.size() != width(input))
    throw std::invalid_argument("affine map does not fit '" + input + "'");
  GraphNode n;
  n.op = GraphOp::kAffine;
  n.inputs = {input};
  n.c = pre_shift;
  n.a = scale;
  n.b = post_shift;
  n.width = width(input);
  return add(std::move(n), "affine");
}

std::string PolicyGraph::clamp(const std::string& input, const Eigen::VectorXf& low,
                               const Eigen::VectorXf& high) {
  if (low.size() != width(input) || high.size() != width(input))
    throw std::invalid_argument("clamp bounds do not fit '" + input + "'");
  // Unbounded on both sides in every column: nothing to do.
  if ((low.array() == -std::numeric_limits<float>::infinity()).all() &&
      (high.array() == std::numeric_limits<float>::infinity()).all())
    return input;
  GraphNode n;
  n.op = GraphOp::kClamp;
  n.inputs = {input};
  n.a = low;
  n.b = high;
  n.width = width(input);
  return add(std::move(n), "clamp");
}

std::string PolicyGraph::one_hot(const std::string& input, float start, int depth) {
  if (width(input) != 1 || depth < 1) throw std::invalid_argument("one-hot of '" + input + "'");
  GraphNode n;
  n.op = GraphOp::kOneHot;
  n.inputs = {input};
  n.start = start;
  n.width = depth;
  return add(std::move(n), "one_hot");
}

std::string PolicyGraph::argmax(const std::string& input) {
  GraphNode n;
  n.op = GraphOp::kArgMax;
  n.inputs = {input};
  n.width = 1;
  return add(std::move(n), "argmax");
}

std::string PolicyGraph::positive(const std::string& input) {
  GraphNode n;
  n.op = GraphOp::kPositive;
  n.inputs = {input};
  n.width = width(input);
  return add(std::move(n), "positive");
}

std::string PolicyGraph::mlp(const std::string& input, const Mlp& net) {
  std::string x = input;
  for (int layer = 0; layer < net.num_layers(); ++layer) {
    x = dense(x, net.weight(layer), net.bias(layer));
    if (layer + 1 < net.num_layers()) x = activation(x, net.activation());
  }
  return x;
}

std::string PolicyGraph::lstm_cell(const std::string& input_gates, const std::string& hidden_gates,
                                   const std::string& cell) {
  const int h = width(cell);
  if (width(input_gates) != 4 * h || width(hidden_gates) != 4 * h)
    throw std::invalid_argument("LSTM cell gates do not fit '" + cell + "'");
  GraphNode n;
  n.op = GraphOp::kLstmCell;
  n.inputs = {input_gates, hidden_gates, cell};
  n.width = 2 * h;
  return add(std::move(n), "lstm");
}

PolicyGraph::LstmStep PolicyGraph::lstm(const std::string& input, const Lstm& net,
                                        const std::string& state) {
  const int hidden = net.hidden_size(), layers = net.num_layers();
  if (width(state) != net.state_size() || width(input) != net.input_size())
    throw std::invalid_argument("LSTM does not fit '" + input + "' and '" + state + "'");
  std::vector<std::string> h_next, c_next;
  std::string x = input;
  for (int layer = 0; layer < layers; ++layer) {
    const std::string h = slice(state, layer * hidden, hidden);
    const std::string c = slice(state, (layers + layer) * hidden, hidden);
    // As Lstm::forward_layer: both biases with the input's product, W_hh h added per step.
    const std::string input_gates =
        dense(x, net.weight_ih(layer), net.bias_ih(layer) + net.bias_hh(layer));
    const std::string hidden_gates =
        dense(h, net.weight_hh(layer), Eigen::VectorXf::Zero(4 * hidden));
    const std::string cell = lstm_cell(input_gates, hidden_gates, c);
    x = slice(cell, 0, hidden);
    h_next.push_back(x);
    c_next.push_back(slice(cell, hidden, hidden));
  }
  h_next.insert(h_next.end(), c_next.begin(), c_next.end());
  return {x, concat(h_next)};
}

std::string PolicyGraph::conv2d(const std::string& input, const Conv2dShape& shape,
                                const Eigen::MatrixXf& weight, const Eigen::VectorXf& bias) {
  if (width(input) != shape.in_size() || weight.rows() != shape.out_channels ||
      weight.cols() != shape.patch_size() || bias.size() != shape.out_channels ||
      shape.out_height() < 1 || shape.out_width() < 1)
    throw std::invalid_argument("convolution does not fit '" + input + "'");
  GraphNode n;
  n.op = GraphOp::kConv2d;
  n.inputs = {input};
  n.weight = weight;
  n.b = bias;
  n.conv = shape;
  n.width = static_cast<int>(shape.out_size());
  return add(std::move(n), "conv");
}

std::string PolicyGraph::nature_cnn(const std::string& input, const NatureCnn& cnn) {
  using RowMajor = Eigen::Matrix<float, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
  TensorMap t;
  cnn.save("cnn", t);  // torch's layouts: (O, C, k, k) and (features, C * H * W), row-major
  auto matrix = [&](const std::string& name, Eigen::Index rows) -> Eigen::MatrixXf {
    const Tensor& w = t.at(name);
    return Eigen::Map<const RowMajor>(w.data<float>(), rows, w.numel() / rows);
  };
  auto vector = [&](const std::string& name) -> Eigen::VectorXf {
    const Tensor& b = t.at(name);
    return Eigen::Map<const Eigen::VectorXf>(b.data<float>(), b.numel());
  };
  std::string x = input;
  if (cnn.normalize_images()) {  // SB3 preprocess_obs: obs.float() / 255
    const Eigen::Index n = width(input);
    x = affine(x, Eigen::VectorXf::Zero(n), Eigen::VectorXf::Constant(n, 1.0f / 255.0f),
               Eigen::VectorXf::Zero(n));
  }
  for (int l = 0; l < NatureCnn::kConvLayers; ++l) {
    Conv2dShape shape = cnn.conv(l);
    if (l > 0) shape.channels_last = false;  // the graph keeps torch's CHW between layers
    const std::string name = "cnn.cnn." + std::to_string(2 * l);
    x = activation(
        conv2d(x, shape, matrix(name + ".weight", shape.out_channels), vector(name + ".bias")),
        Activation::kReLU);
  }
  return activation(
      dense(x, matrix("cnn.linear.0.weight", cnn.features_dim()), vector("cnn.linear.0.bias")),
      Activation::kReLU);
}

namespace {

float activate(Activation act, float v) {
  switch (act) {
    case Activation::kTanh: return std::tanh(v);
    case Activation::kReLU: return v > 0.0f ? v : 0.0f;
    case Activation::kELU: return v > 0.0f ? v : std::exp(v) - 1.0f;
    case Activation::kLeakyReLU: return v > 0.0f ? v : kLeakyReLUSlope * v;
    case Activation::kGELU:
      // torch.nn.GELU, x (1 + erf(x / sqrt(2))) / 2, as x erfc(-x / sqrt(2)) / 2 in double:
      // no cancellation for negative x.
      return static_cast<float>(0.5 * v * std::erfc(-v * 0.70710678118654752));
  }
  return v;
}

float sigmoid(float v) { return 1.0f / (1.0f + std::exp(-v)); }

}  // namespace

void run_node(const GraphNode& n, std::span<const ConstGraphBlock> inputs, GraphBlock y) {
  const ConstGraphBlock& x = inputs.front();
  const Eigen::Index batch = y.cols();
  switch (n.op) {
    case GraphOp::kConcat: {
      Eigen::Index row = 0;
      for (const ConstGraphBlock& part : inputs) {
        y.middleRows(row, part.rows()) = part;
        row += part.rows();
      }
      return;
    }
    case GraphOp::kSlice: y = x.middleRows(n.begin, n.width); return;
    case GraphOp::kDense:
      y.noalias() = n.weight * x;
      y.colwise() += n.b;
      return;
    case GraphOp::kActivation:
      y = x.unaryExpr([&](float v) { return activate(n.activation, v); });
      return;
    case GraphOp::kAffine:
      for (Eigen::Index j = 0; j < batch; ++j)
        for (int k = 0; k < n.width; ++k) y(k, j) = (x(k, j) + n.c(k)) * n.a(k) + n.b(k);
      return;
    case GraphOp::kClamp:
      for (Eigen::Index j = 0; j < batch; ++j)
        for (int k = 0; k < n.width; ++k) y(k, j) = std::min(std::max(x(k, j), n.a(k)), n.b(k));
      return;
    case GraphOp::kOneHot:
      for (Eigen::Index j = 0; j < batch; ++j)
        for (int k = 0; k < n.width; ++k)
          y(k, j) = std::nearbyint(x(0, j)) - n.start == static_cast<float>(k) ? 1.0f : 0.0f;
      return;
    case GraphOp::kArgMax:
      for (Eigen::Index j = 0; j < batch; ++j) {
        Eigen::Index best = 0;
        for (Eigen::Index k = 1; k < x.rows(); ++k)
          if (x(k, j) > x(best, j)) best = k;
        y(0, j) = static_cast<float>(best);
      }
      return;
    case GraphOp::kPositive: y = (x.array() > 0.0f).cast<float>(); return;
    case GraphOp::kLstmCell: {
      const ConstGraphBlock& hidden_gates = inputs[1];
      const ConstGraphBlock& c = inputs[2];
      const int h = n.width / 2;
      for (Eigen::Index j = 0; j < batch; ++j)
        for (int k = 0; k < h; ++k) {
          auto gate = [&](int g) { return x(g * h + k, j) + hidden_gates(g * h + k, j); };
          const float c_next = sigmoid(gate(1)) * c(k, j) + sigmoid(gate(0)) * std::tanh(gate(2));
          y(k, j) = sigmoid(gate(3)) * std::tanh(c_next);
          y(h + k, j) = c_next;
        }
      return;
    }
    case GraphOp::kConv2d: {
      // A direct convolution, output (o, y, x), each sum started from the bias.
      const Conv2dShape& s = n.conv;
      const int oh = s.out_height(), ow = s.out_width(), k = s.kernel;
      auto in_index = [&](int c, int row, int col) -> Eigen::Index {
        return s.channels_last ? (Eigen::Index{row} * s.in_width + col) * s.in_channels + c
                               : (Eigen::Index{c} * s.in_height + row) * s.in_width + col;
      };
      for (Eigen::Index j = 0; j < batch; ++j)
        for (int o = 0; o < s.out_channels; ++o)
          for (int oy = 0; oy < oh; ++oy)
            for (int ox = 0; ox < ow; ++ox) {
              float sum = n.b(o);
              for (int c = 0; c < s.in_channels; ++c)
                for (int i = 0; i < k; ++i)
                  for (int jj = 0; jj < k; ++jj)
                    sum += n.weight(o, (Eigen::Index{c} * k + i) * k + jj) *
                           x(in_index(c, oy * s.stride + i, ox * s.stride + jj), j);
              y((Eigen::Index{o} * oh + oy) * ow + ox, j) = sum;
            }
      return;
    }
  }
}

std::map<std::string, Eigen::MatrixXf> evaluate_graph(const PolicyGraph& graph,
                                                      const std::vector<Eigen::MatrixXf>& inputs) {
  const size_t observations = graph.inputs().size();
  if (inputs.size() != observations + (graph.state_width() > 0 ? 1 : 0))
    throw std::invalid_argument("evaluate_graph: " + std::to_string(observations) +
                                " observation inputs expected" +
                                (graph.state_width() > 0 ? " and the state" : ""));
  std::map<std::string, Eigen::MatrixXf> values;
  const Eigen::Index batch = inputs.empty() ? 0 : inputs.front().cols();
  if (graph.state_width() > 0) {
    const Eigen::MatrixXf& state = inputs.back();
    if (state.rows() != graph.state_width() || state.cols() != batch)
      throw std::invalid_argument("evaluate_graph: the state must be " +
                                  std::to_string(graph.state_width()) + " x batch");
    values[PolicyGraph::kStateInput] = state;
  }
  for (size_t i = 0; i < observations; ++i) {
    if (inputs[i].rows() != graph.inputs()[i].width || inputs[i].cols() != batch)
      throw std::invalid_argument("evaluate_graph: input '" + graph.inputs()[i].name +
                                  "' must be " + std::to_string(graph.inputs()[i].width) +
                                  " x batch");
    values[graph.inputs()[i].name] = inputs[i];
  }
  std::vector<ConstGraphBlock> in;
  for (const GraphNode& n : graph.nodes()) {
    in.clear();
    for (const std::string& name : n.inputs) {
      const Eigen::MatrixXf& m = values.at(name);
      in.emplace_back(m.data(), m.rows(), m.cols(), Eigen::OuterStride<>(m.rows()));
    }
    Eigen::MatrixXf y(n.width, batch);
    run_node(n, in, GraphBlock(y.data(), y.rows(), y.cols(), Eigen::OuterStride<>(y.rows())));
    values[n.output] = std::move(y);
  }
  return values;
}

}  // namespace rlrun
