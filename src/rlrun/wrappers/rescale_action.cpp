#include "rlrun/wrappers/rescale_action.hpp"

#include <Eigen/Core>

#include "rlrun/core/plural.hpp"
#include "rlrun/nn/policy_graph.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace rlrun {

namespace {

std::vector<float> broadcast(const std::vector<double>& values, int dims, const char* name) {
  if (values.size() == 1) return std::vector<float>(dims, static_cast<float>(values[0]));
  if (static_cast<int>(values.size()) != dims)
    throw std::invalid_argument(std::string("RescaleAction: ") + name + " has " +
                                count_of(static_cast<int64_t>(values.size()), "value") +
                                ", the action space " + count_of(dims, "dimension"));
  return std::vector<float>(values.begin(), values.end());
}

}  // namespace

RescaleAction::RescaleAction(EnvPtr inner, const Config& config) : ActionWrapper(std::move(inner)) {
  const Space& inner_space = inner_->action_space();
  if (!inner_space.is_box())
    throw std::invalid_argument("RescaleAction needs a Box action space, " + inner_->id() +
                                " has " + inner_space.describe());
  const int dims = inner_space.flat_dim();
  const std::vector<float> lo = broadcast(config.min_action.values, dims, "min_action");
  const std::vector<float> hi = broadcast(config.max_action.values, dims, "max_action");
  gradient_.resize(dims);
  intercept_.resize(dims);
  for (int i = 0; i < dims; ++i) {
    const float low = inner_space.low()[i], high = inner_space.high()[i];
    if (!std::isfinite(low) || !std::isfinite(high))
      throw std::invalid_argument("RescaleAction needs finite action bounds, " + inner_->id() +
                                  " has " + inner_space.describe());
    if (!(lo[i] < hi[i]))
      throw std::invalid_argument("RescaleAction: min_action must be below max_action");
    // Gymnasium 1.0: gradient = (high - low) / (max - min); intercept = gradient * -min + low.
    gradient_[i] = (high - low) / (hi[i] - lo[i]);
    intercept_[i] = gradient_[i] * -lo[i] + low;
  }
  space_ = Space::box(lo, hi, inner_space.shape());
  inner_low_.assign(inner_space.low().begin(), inner_space.low().end());
  inner_high_.assign(inner_space.high().begin(), inner_space.high().end());
  inner_action_.resize(dims);
}

std::string RescaleAction::export_action(PolicyGraph& graph, const std::string& action) const {
  const Space& inner_space = inner_->action_space();
  const int n = inner_space.flat_dim();
  const Eigen::Map<const Eigen::VectorXf> gradient(gradient_.data(), n),
      intercept(intercept_.data(), n), low(inner_space.low().data(), n),
      high(inner_space.high().data(), n);
  return graph.clamp(graph.affine(action, Eigen::VectorXf::Zero(n), gradient, intercept), low,
                     high);
}

std::span<const float> RescaleAction::map_action(std::span<const float> action) {
  for (size_t i = 0; i < inner_action_.size(); ++i)
    inner_action_[i] =
        std::clamp(gradient_[i] * action[i] + intercept_[i], inner_low_[i], inner_high_[i]);
  return inner_action_;
}

}  // namespace rlrun
