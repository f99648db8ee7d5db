#pragma once
// A FrozenPolicy (env/policy_pool.hpp) read from a PolicyGraph (nn/policy_graph.hpp): the graph
// an algorithm exports for its deterministic action (Algorithm::export_policy, or a loaded
// model's build_model_graph) ends in the argmax of the categorical's logits; this runs the graph
// up to those logits. The graph is copied and only read, so the policy is thread-safe and a
// snapshot stays as it was while the learner trains on.
#include <string>

#include "rlrun/env/policy_pool.hpp"
#include "rlrun/nn/policy_graph.hpp"

namespace rlrun {

class GraphPolicy : public FrozenPolicy {
 public:
  // Throws ExportError when the graph's action is not the argmax of one tensor (a policy that
  // is not a single categorical over Discrete actions) or the graph has several inputs.
  explicit GraphPolicy(PolicyGraph graph);
  int num_actions() const override { return num_actions_; }
  int observation_width() const { return graph_.observation_width(); }
  void logits(std::span<const float> obs, std::span<float> out) const override;

 private:
  PolicyGraph graph_;
  std::string logits_;  // the argmax node's input
  int num_actions_ = 0;
};

}  // namespace rlrun
