#include "rlrun/wrappers/clip_action.hpp"

#include <Eigen/Core>

#include "rlrun/nn/policy_graph.hpp"

#include <algorithm>
#include <limits>
#include <stdexcept>

namespace rlrun {

ClipAction::ClipAction(EnvPtr inner, const Config& /*config*/) : ActionWrapper(std::move(inner)) {
  const Space& inner_space = inner_->action_space();
  if (!inner_space.is_box())
    throw std::invalid_argument("ClipAction needs a Box action space, " + inner_->id() + " has " +
                                inner_space.describe());
  const float inf = std::numeric_limits<float>::infinity();
  space_ = Space::box(-inf, inf, inner_space.shape());
  clipped_.resize(inner_space.flat_dim());
}

std::string ClipAction::export_action(PolicyGraph& graph, const std::string& action) const {
  const Space& inner_space = inner_->action_space();
  const int n = inner_space.flat_dim();
  return graph.clamp(action, Eigen::Map<const Eigen::VectorXf>(inner_space.low().data(), n),
                     Eigen::Map<const Eigen::VectorXf>(inner_space.high().data(), n));
}

std::span<const float> ClipAction::map_action(std::span<const float> action) {
  const Space& inner_space = inner_->action_space();
  for (size_t i = 0; i < clipped_.size(); ++i)
    clipped_[i] = std::clamp(action[i], inner_space.low()[i], inner_space.high()[i]);
  return clipped_;
}

}  // namespace rlrun
