#include "rlrun/wrappers/box_as_discrete.hpp"

#include <cmath>
#include <stdexcept>

namespace rlrun {

BoxAsDiscrete::BoxAsDiscrete(EnvPtr inner, const Config& config)
    : Wrapper(std::move(inner)), bins_(config.bins) {
  const Space& inner_space = inner_->action_space();
  if (!inner_space.is_box())
    throw std::invalid_argument("BoxAsDiscrete needs a Box action space, " + inner_->id() +
                                " has " + inner_space.describe());
  if (bins_ < 2) throw std::invalid_argument("BoxAsDiscrete: bins must be >= 2");
  const int dims = inner_space.flat_dim();
  double count = std::pow(static_cast<double>(bins_), dims);
  if (count > (1 << 24)) throw std::invalid_argument("BoxAsDiscrete: bins^dims is too large");
  for (int i = 0; i < dims; ++i)
    if (!std::isfinite(inner_space.low()[i]) || !std::isfinite(inner_space.high()[i]))
      throw std::invalid_argument("BoxAsDiscrete needs finite action bounds");
  space_ = Space::discrete(static_cast<int64_t>(count));
  box_action_.resize(dims);
}

StepResult BoxAsDiscrete::step(std::span<const float> action, std::span<float> obs) {
  const Space& inner_space = inner_->action_space();
  int64_t index = static_cast<int64_t>(action[0]);
  if (index < 0 || index >= space_.n())
    throw std::invalid_argument("BoxAsDiscrete: action " + std::to_string(index) + " outside " +
                                space_.describe());
  for (size_t i = 0; i < box_action_.size(); ++i) {
    const int bin = static_cast<int>(index % bins_);
    index /= bins_;
    const float low = inner_space.low()[i], high = inner_space.high()[i];
    box_action_[i] = low + (high - low) * static_cast<float>(bin) / static_cast<float>(bins_ - 1);
  }
  return inner_->step(box_action_, obs);
}

}  // namespace rlrun
