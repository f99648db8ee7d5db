#pragma once
// ClipAction: gymnasium/wrappers/transform_action.py. Actions are clipped to the inner env's
// Box bounds, and the action space the agent sees becomes Box(-inf, inf) of the same shape, as
// in Gymnasium 1.0 (so an algorithm does not clip them itself first). Algorithms that need
// bounded actions (SAC, TD3, DDPG squash into the bounds) refuse such a space: use
// RescaleAction with them instead.
#include <vector>

#include "rlrun/wrappers/action_wrapper.hpp"
#include "rlrun/wrappers/no_options.hpp"

namespace rlrun {

class ClipAction : public ActionWrapper {
 public:
  using Config = NoOptions;
  // Throws std::invalid_argument for a non-Box action space.
  ClipAction(EnvPtr inner, const Config& config);
  explicit ClipAction(EnvPtr inner) : ClipAction(std::move(inner), Config()) {}

  std::string export_action(PolicyGraph& graph, const std::string& action) const override;

 private:
  // The action clipped to the inner env's bounds.
  std::span<const float> map_action(std::span<const float> action) override;
  std::vector<float> clipped_;
};

}  // namespace rlrun
