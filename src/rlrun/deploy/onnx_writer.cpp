#include "rlrun/deploy/onnx_writer.hpp"

#include <bit>
#include <limits>
#include <vector>

#include "rlrun/core/protobuf_writer.hpp"
#include "rlrun/core/utf8_text.hpp"
#include "rlrun/deploy/graph_numbers.hpp"

namespace rlrun {

namespace {

// Field numbers and enum values of onnx/onnx.proto.
namespace model_proto {
constexpr int kIrVersion = 1, kProducerName = 2, kProducerVersion = 3, kDocString = 6, kGraph = 7,
              kOpsetImport = 8, kMetadataProps = 14;
}
namespace graph_proto {
constexpr int kNode = 1, kName = 2, kInitializer = 5, kInput = 11, kOutput = 12;
}
namespace node_proto {
constexpr int kInput = 1, kOutput = 2, kName = 3, kOpType = 4, kAttribute = 5;
}
namespace attribute_proto {
constexpr int kName = 1, kF = 2, kI = 3, kInts = 8, kType = 20;
constexpr int kTypeFloat = 1, kTypeInt = 2, kTypeInts = 7;
}  // namespace attribute_proto
namespace tensor_proto {
constexpr int kDims = 1, kDataType = 2, kName = 8, kRawData = 9;
constexpr int kFloat = 1, kInt64 = 7;
}  // namespace tensor_proto

class OnnxGraphWriter {
 public:
  explicit OnnxGraphWriter(const PolicyGraph& graph) : graph_(graph) {}

  std::string model() {
    ProtoWriter g;
    g.bytes(graph_proto::kName, "rlrun_policy");
    for (const GraphInput& in : graph_.inputs())
      g.message(graph_proto::kInput, value_info(in.name, in.width));
    if (graph_.state_width() > 0)
      g.message(graph_proto::kInput, value_info(PolicyGraph::kStateInput, graph_.state_width()));
    for (const GraphNode& n : graph_.nodes()) emit(n);
    output("action", graph_.action());
    if (!graph_.value().empty()) output("value", graph_.value());
    if (graph_.state_width() > 0) output(PolicyGraph::kStateOutput, graph_.state_output());
    for (const ProtoWriter& node : nodes_) g.message(graph_proto::kNode, node);
    for (const ProtoWriter& init : initializers_) g.message(graph_proto::kInitializer, init);
    for (const ProtoWriter& out : outputs_) g.message(graph_proto::kOutput, out);

    ProtoWriter m;
    m.int64(model_proto::kIrVersion, kOnnxIrVersion);
    m.bytes(model_proto::kProducerName, "rlrun");
    const auto version = graph_.metadata.find("rlrun_version");
    if (version != graph_.metadata.end())
      m.bytes(model_proto::kProducerVersion, printable_utf8(version->second));
    m.bytes(model_proto::kDocString,
            "deterministic policy exported by `rlrun export`: observation -> action");
    m.message(model_proto::kGraph, g);
    ProtoWriter opset;
    opset.bytes(1, "");  // the default domain (ai.onnx)
    opset.int64(2, kOnnxOpset);
    m.message(model_proto::kOpsetImport, opset);
    // Protobuf strings must be UTF-8, and the metadata comes from the model file (untrusted).
    for (const auto& [key, value] : graph_.metadata) {
      ProtoWriter entry;
      entry.bytes(1, printable_utf8(key)).bytes(2, printable_utf8(value));
      m.message(model_proto::kMetadataProps, entry);
    }
    return m.str();
  }

 private:
  // ValueInfoProto of a float tensor [batch, width].
  static ProtoWriter value_info(const std::string& name, int width) {
    ProtoWriter batch, columns, shape, tensor, type, info;
    batch.bytes(2, "batch");  // dim_param
    columns.int64(1, width);  // dim_value
    shape.message(1, batch).message(1, columns);
    tensor.int64(1, tensor_proto::kFloat).message(2, shape);  // elem_type, shape
    type.message(1, tensor);                                  // tensor_type
    info.bytes(1, name).message(2, type);
    return info;
  }

  // Names of the ONNX-only tensors; the "rlrun/" prefix keeps them apart from the graph's own.
  std::string fresh(const std::string& base) {
    return "rlrun/" + base + "_" + std::to_string(counter_++);
  }

  // A constant tensor (initializer); returns its name.
  std::string constant(const std::string& base, const std::vector<int64_t>& dims, const float* data,
                       size_t count) {
    const std::string name = fresh(base);
    ProtoWriter t;
    for (int64_t d : dims) t.int64(tensor_proto::kDims, d);
    t.int64(tensor_proto::kDataType, tensor_proto::kFloat);
    t.bytes(tensor_proto::kName, name);
    // raw_data: little-endian float32, which this machine's memory already is.
    static_assert(std::endian::native == std::endian::little, "raw_data is little-endian");
    t.bytes(tensor_proto::kRawData,
            std::string_view(reinterpret_cast<const char*>(data), count * sizeof(float)));
    initializers_.push_back(std::move(t));
    return name;
  }
  std::string constant(const std::string& base, const Eigen::VectorXf& v) {
    return constant(base, {v.size()}, v.data(), static_cast<size_t>(v.size()));
  }
  std::string int64_constant(const std::string& base, int64_t value) {
    return int64_constant(base, std::vector<int64_t>{value});
  }
  // A 1-D int64 tensor (a Slice bound, a Reshape shape).
  std::string int64_constant(const std::string& base, const std::vector<int64_t>& values) {
    const std::string name = fresh(base);
    ProtoWriter t;
    t.int64(tensor_proto::kDims, static_cast<int64_t>(values.size()));
    t.int64(tensor_proto::kDataType, tensor_proto::kInt64);
    t.bytes(tensor_proto::kName, name);
    t.bytes(tensor_proto::kRawData, std::string_view(reinterpret_cast<const char*>(values.data()),
                                                     values.size() * sizeof(int64_t)));
    initializers_.push_back(std::move(t));
    return name;
  }

  struct Attribute {
    std::string name;
    bool is_float = false;
    float f = 0;
    int64_t i = 0;
    std::vector<int64_t> ints;  // a list attribute when not empty
  };
  static Attribute int_attr(const std::string& name, int64_t i) { return {name, false, 0, i, {}}; }
  static Attribute float_attr(const std::string& name, float f) { return {name, true, f, 0, {}}; }
  static Attribute ints_attr(const std::string& name, std::vector<int64_t> ints) {
    return {name, false, 0, 0, std::move(ints)};
  }

  // One NodeProto; returns its output's name (`output`, or a fresh one).
  std::string node(const std::string& op, const std::vector<std::string>& inputs,
                   std::string output = "", const std::vector<Attribute>& attributes = {}) {
    if (output.empty()) output = fresh(op);
    ProtoWriter n;
    for (const std::string& in : inputs) n.bytes(node_proto::kInput, in);
    n.bytes(node_proto::kOutput, output);
    n.bytes(node_proto::kName, output);
    n.bytes(node_proto::kOpType, op);
    for (const Attribute& a : attributes) {
      ProtoWriter attr;
      attr.bytes(attribute_proto::kName, a.name);
      if (!a.ints.empty()) {
        for (int64_t v : a.ints) attr.int64(attribute_proto::kInts, v);
        attr.int64(attribute_proto::kType, attribute_proto::kTypeInts);
      } else if (a.is_float)
        attr.float32(attribute_proto::kF, a.f)
            .int64(attribute_proto::kType, attribute_proto::kTypeFloat);
      else
        attr.int64(attribute_proto::kI, a.i)
            .int64(attribute_proto::kType, attribute_proto::kTypeInt);
      n.message(node_proto::kAttribute, attr);
    }
    nodes_.push_back(std::move(n));
    return output;
  }

  static bool all(const Eigen::VectorXf& v, float value) { return (v.array() == value).all(); }

  // torch.nn.GELU (approximate='none'), x (1 + erf(x / sqrt(2))) / 2, from Mul, Erf and Add:
  // ONNX's Gelu operator exists only from opset 20 (kOnnxOpset is 13), Erf from opset 9.
  void gelu(const std::string& x, const std::string& out) {
    const auto scalar = [&](const std::string& base, float value) {
      return constant(base, {}, &value, 1);
    };
    const std::string scaled = node("Mul", {x, scalar("inv_sqrt2", 0.70710678118654752f)});
    const std::string erf = node("Erf", {scaled});
    const std::string one_plus_erf = node("Add", {erf, scalar("one", 1.0f)});
    const std::string half_x = node("Mul", {x, scalar("half", 0.5f)});
    node("Mul", {half_x, one_plus_erf}, out);
  }

  void emit(const GraphNode& n) {
    const std::string& x = n.inputs.front();
    const std::string& out = n.output;
    switch (n.op) {
      case GraphOp::kConcat: node("Concat", n.inputs, out, {int_attr("axis", 1)}); return;
      case GraphOp::kSlice:
        node("Slice",
             {x, int64_constant("starts", n.begin), int64_constant("ends", n.begin + n.width),
              int64_constant("axes", 1)},
             out);
        return;
      case GraphOp::kDense: {
        // torch's Linear layout, [out, in] row-major: the Eigen (column-major) transpose.
        const Eigen::Matrix<float, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> w = n.weight;
        const std::string weight = constant(out + "_weight", {w.rows(), w.cols()}, w.data(),
                                            static_cast<size_t>(w.size()));
        node("Gemm", {x, weight, constant(out + "_bias", n.b)}, out, {int_attr("transB", 1)});
        return;
      }
      case GraphOp::kActivation:
        switch (n.activation) {
          case Activation::kTanh: node("Tanh", {x}, out); return;
          case Activation::kReLU: node("Relu", {x}, out); return;
          case Activation::kELU: node("Elu", {x}, out, {float_attr("alpha", 1.0f)}); return;
          case Activation::kLeakyReLU:
            node("LeakyRelu", {x}, out, {float_attr("alpha", kLeakyReLUSlope)});
            return;
          case Activation::kGELU: gelu(x, out); return;
        }
        return;
      case GraphOp::kAffine: {
        std::string y = x;
        if (!all(n.c, 0.0f)) y = node("Add", {y, constant("shift", n.c)});
        if (!all(n.a, 1.0f)) y = node("Mul", {y, constant("scale", n.a)});
        if (!all(n.b, 0.0f)) y = node("Add", {y, constant("offset", n.b)});
        node("Identity", {y}, out);
        return;
      }
      case GraphOp::kClamp: {
        constexpr float kInf = std::numeric_limits<float>::infinity();
        std::string y = x;
        if (!all(n.a, -kInf)) y = node("Max", {y, constant("low", n.a)});
        if (!all(n.b, kInf)) y = node("Min", {y, constant("high", n.b)});
        node("Identity", {y}, out);
        return;
      }
      case GraphOp::kOneHot: {
        Eigen::VectorXf slots(n.width);
        for (int k = 0; k < n.width; ++k) slots(k) = static_cast<float>(k);
        const Eigen::VectorXf start = Eigen::VectorXf::Constant(1, n.start);
        const std::string slot = node("Sub", {node("Round", {x}), constant("start", start)});
        node("Cast", {node("Equal", {slot, constant("slots", slots)})}, out,
             {int_attr("to", tensor_proto::kFloat)});
        return;
      }
      case GraphOp::kArgMax:
        node("Cast", {node("ArgMax", {x}, "", {int_attr("axis", 1), int_attr("keepdims", 1)})}, out,
             {int_attr("to", tensor_proto::kFloat)});
        return;
      case GraphOp::kConv2d: emit_conv(n); return;
      case GraphOp::kLstmCell: emit_lstm_cell(n); return;
      case GraphOp::kPositive: {
        const float zero = 0.0f;
        node("Cast", {node("Greater", {x, constant("zero", {}, &zero, 1)})}, out,
             {int_attr("to", tensor_proto::kFloat)});
        return;
      }
    }
  }

  // [batch, width] -> the image as ONNX's Conv reads it, [batch, C, H, W] (a Transpose from
  // channels-last), Conv, and back to [batch, O * OH * OW] in (o, y, x) order.
  void emit_conv(const GraphNode& n) {
    const Conv2dShape& s = n.conv;
    const std::string& x = n.inputs.front();
    const int64_t c = s.in_channels, h = s.in_height, w = s.in_width;
    const std::string image =
        s.channels_last
            ? node("Transpose", {node("Reshape", {x, int64_constant("shape", {-1, h, w, c})})}, "",
                   {ints_attr("perm", {0, 3, 1, 2})})
            : node("Reshape", {x, int64_constant("shape", {-1, c, h, w})});
    // torch's weight (O, C, k, k) row-major: the rows of n.weight, each in (c, i, j) order.
    const Eigen::Matrix<float, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> weight = n.weight;
    const std::string kernel =
        constant(n.output + "_weight", {s.out_channels, c, s.kernel, s.kernel}, weight.data(),
                 static_cast<size_t>(weight.size()));
    const std::string conv = node("Conv", {image, kernel, constant(n.output + "_bias", n.b)}, "",
                                  {ints_attr("kernel_shape", {s.kernel, s.kernel}),
                                   ints_attr("strides", {s.stride, s.stride})});
    node("Reshape", {conv, int64_constant("shape", {-1, n.width})}, n.output);
  }

  // One LSTM layer's step from Add, Slice, Sigmoid, Tanh and Mul (ONNX's own LSTM operator
  // runs whole sequences and keeps its state apart; a step is these few nodes).
  void emit_lstm_cell(const GraphNode& n) {
    const int64_t h = n.width / 2;
    const std::string gates = node("Add", {n.inputs[0], n.inputs[1]});
    auto gate = [&](int64_t k) {
      return node("Slice", {gates, int64_constant("starts", k * h),
                            int64_constant("ends", (k + 1) * h), int64_constant("axes", 1)});
    };
    const std::string i = node("Sigmoid", {gate(0)}), f = node("Sigmoid", {gate(1)});
    const std::string g = node("Tanh", {gate(2)}), o = node("Sigmoid", {gate(3)});
    const std::string c = node("Add", {node("Mul", {f, n.inputs[2]}), node("Mul", {i, g})});
    const std::string hidden = node("Mul", {o, node("Tanh", {c})});
    node("Concat", {hidden, c}, n.output, {int_attr("axis", 1)});
  }

  void output(const std::string& name, const std::string& tensor) {
    node("Identity", {tensor}, name);
    outputs_.push_back(value_info(name, graph_.width(tensor)));
  }

  const PolicyGraph& graph_;
  std::vector<ProtoWriter> nodes_, initializers_, outputs_;
  int counter_ = 0;
};

}  // namespace

std::string onnx_model_bytes(const PolicyGraph& graph) {
  if (graph.action().empty()) throw ExportError("the policy graph has no action output");
  for (const GraphInput& in : graph.inputs()) {
    // Input names are the file's interface: refused, not rewritten, when they cannot be one.
    if (in.name == "action" || in.name == "value" ||
        (graph.state_width() > 0 && in.name == PolicyGraph::kStateOutput))
      throw ExportError("a Dict observation key named '" + in.name +
                        "' would clash with the ONNX output of that name");
    if (in.name.rfind("rlrun/", 0) == 0)
      throw ExportError("a Dict observation key named '" + printable_utf8(in.name) +
                        "' would clash with the exporter's own tensor names (rlrun/...)");
    if (printable_utf8(in.name) != in.name)
      throw ExportError("a Dict observation key '" + printable_utf8(in.name) +
                        "' is not printable UTF-8 text, which an ONNX input name must be");
  }
  check_graph_numbers(graph);
  return OnnxGraphWriter(graph).model();
}

}  // namespace rlrun
