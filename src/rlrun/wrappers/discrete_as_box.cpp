#include "rlrun/wrappers/discrete_as_box.hpp"

#include "rlrun/nn/policy_graph.hpp"

#include <stdexcept>

namespace rlrun {

DiscreteAsBox::DiscreteAsBox(EnvPtr inner, const Config&) : Wrapper(std::move(inner)) {
  const Space& inner_space = inner_->action_space();
  if (!inner_space.is_discrete())
    throw std::invalid_argument("DiscreteAsBox needs a Discrete action space, " + inner_->id() +
                                " has " + inner_space.describe());
  space_ = Space::box(-1.0f, 1.0f, {static_cast<int>(inner_space.n())});
}

std::string DiscreteAsBox::export_action(PolicyGraph& graph, const std::string& action) const {
  const std::string index = graph.argmax(action);
  const float start = static_cast<float>(inner_->action_space().start());
  if (start == 0.0f) return index;
  return graph.affine(index, Eigen::VectorXf::Zero(1), Eigen::VectorXf::Ones(1),
                      Eigen::VectorXf::Constant(1, start));
}

StepResult DiscreteAsBox::step(std::span<const float> action, std::span<float> obs) {
  size_t best = 0;
  for (size_t i = 1; i < action.size(); ++i)
    if (action[i] > action[best]) best = i;
  discrete_action_ =
      static_cast<float>(inner_->action_space().start() + static_cast<int64_t>(best));
  return inner_->step({&discrete_action_, 1}, obs);
}

}  // namespace rlrun
