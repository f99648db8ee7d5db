#include "rlrun/deploy/graph_numbers.hpp"

#include <cmath>
#include <string>

namespace rlrun {

namespace {

// A bound may be infinite (HUGE_VALF in C); every other number must be finite.
enum class Kind { kFinite, kBound };

// `what`: "dense_3 (Dense weight)"; a vector is one column.
void check(const Eigen::Ref<const Eigen::MatrixXf>& m, Kind kind, const std::string& what) {
  for (Eigen::Index j = 0; j < m.cols(); ++j)
    for (Eigen::Index i = 0; i < m.rows(); ++i) {
      const float v = m(i, j);
      if (kind == Kind::kBound ? !std::isnan(v) : std::isfinite(v)) continue;
      const std::string where = m.cols() == 1
                                    ? "index " + std::to_string(i)
                                    : "row " + std::to_string(i) + ", column " + std::to_string(j);
      throw ExportError("the policy's " + what + " holds " +
                        (std::isnan(v) ? "nan" : (v > 0 ? "inf" : "-inf")) + " at " + where +
                        (kind == Kind::kBound ? "" : " (only bounds may be infinite)") +
                        ": the model's weights or normalisation statistics do not fit float32");
    }
}

}  // namespace

void check_graph_numbers(const PolicyGraph& graph) {
  for (const GraphNode& n : graph.nodes()) {
    const std::string& name = n.output;
    switch (n.op) {
      case GraphOp::kDense:
        check(n.weight, Kind::kFinite, name + " (Dense weight)");
        check(n.b, Kind::kFinite, name + " (Dense bias)");
        break;
      case GraphOp::kAffine:
        check(n.c, Kind::kFinite, name + " (Affine shift)");
        check(n.a, Kind::kFinite, name + " (Affine scale)");
        check(n.b, Kind::kFinite, name + " (Affine offset)");
        break;
      case GraphOp::kClamp:
        check(n.a, Kind::kBound, name + " (Clamp low)");
        check(n.b, Kind::kBound, name + " (Clamp high)");
        break;
      case GraphOp::kConv2d:
        check(n.weight, Kind::kFinite, name + " (Conv2d weight)");
        check(n.b, Kind::kFinite, name + " (Conv2d bias)");
        break;
      case GraphOp::kOneHot:
        check(Eigen::VectorXf::Constant(1, n.start), Kind::kFinite, name + " (OneHot start)");
        break;
      case GraphOp::kConcat:
      case GraphOp::kSlice:
      case GraphOp::kActivation:
      case GraphOp::kArgMax:
      case GraphOp::kPositive:
      case GraphOp::kLstmCell: break;
    }
  }
}

}  // namespace rlrun
