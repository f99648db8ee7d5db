#include "rlrun/algos/algorithm.hpp"

#include "rlrun/nn/policy_graph.hpp"

namespace rlrun {

void Algorithm::export_policy(PolicyGraph& /*graph*/, const std::string& /*obs*/,
                              bool /*with_value*/) const {
  throw ExportError(id() + " cannot be exported yet");
}

}  // namespace rlrun
