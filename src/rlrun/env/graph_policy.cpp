#include "rlrun/env/graph_policy.hpp"

#include <stdexcept>

namespace rlrun {

GraphPolicy::GraphPolicy(PolicyGraph graph) : graph_(std::move(graph)) {
  if (graph_.state_width() > 0)
    throw ExportError(
        "a self-play opponent must be feed-forward: this policy has a recurrent "
        "state");
  if (graph_.inputs().size() != 1)
    throw ExportError("a self-play opponent reads one observation input, the graph has " +
                      std::to_string(graph_.inputs().size()));
  for (const GraphNode& node : graph_.nodes())
    if (node.output == graph_.action() && node.op == GraphOp::kArgMax) logits_ = node.inputs[0];
  if (logits_.empty())
    throw ExportError(
        "a self-play opponent needs a policy whose action is the argmax of its logits (one "
        "categorical over a Discrete action space, no action wrappers)");
  num_actions_ = graph_.width(logits_);
}

void GraphPolicy::logits(std::span<const float> obs, std::span<float> out) const {
  if (static_cast<int>(obs.size()) != graph_.observation_width() ||
      static_cast<int>(out.size()) != num_actions_)
    throw std::invalid_argument("GraphPolicy: an observation of " + std::to_string(obs.size()) +
                                " floats for a policy of " +
                                std::to_string(graph_.observation_width()));
  const Eigen::MatrixXf input =
      Eigen::Map<const Eigen::MatrixXf>(obs.data(), static_cast<Eigen::Index>(obs.size()), 1);
  const auto values = evaluate_graph(graph_, {input});
  const Eigen::MatrixXf& logits = values.at(logits_);
  for (int a = 0; a < num_actions_; ++a) out[a] = logits(a, 0);
}

}  // namespace rlrun
