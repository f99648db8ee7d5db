#pragma once
// ClipAction: gymnasium/wrappers/transform_action.py. Actions are clipped to the inner env's
// Box bounds, and the action space the agent sees becomes Box(-inf, inf) of the same shape, as
// in Gymnasium 1.0 (so an algorithm does not clip them itself first). Algorithms that need
// bounded actions (SAC, TD3, DDPG squash into the bounds) refuse such a space: use
// RescaleAction with them instead.
#include <vector>

#include "rlrun/env/split_step.hpp"
#include "rlrun/env/wrapper.hpp"

namespace rlrun {

class ClipAction : public Wrapper, public SplitStep {
 public:
  struct Config {
    template <class V>
    void visit(V& /*v*/) {}
  };
  // Throws std::invalid_argument for a non-Box action space.
  ClipAction(EnvPtr inner, const Config& config);
  explicit ClipAction(EnvPtr inner) : ClipAction(std::move(inner), Config()) {}

  const Space& action_space() const override { return space_; }
  StepResult step(std::span<const float> action, std::span<float> obs) override;
  // The two halves of step() (env/split_step.hpp): the clipped action is handed on.
  bool steps_asynchronously() const override { return asynchronous_steps(*inner_) != nullptr; }
  void start_step(std::span<const float> action) override {
    asynchronous_steps(*inner_)->start_step(clip(action));
  }
  StepResult finish_step(std::span<float> obs) override {
    return asynchronous_steps(*inner_)->finish_step(obs);
  }

  std::string export_observation(PolicyGraph& /*graph*/, const std::string& obs) const override {
    return obs;
  }
  std::string export_action(PolicyGraph& graph, const std::string& action) const override;

 private:
  std::span<const float> clip(std::span<const float> action);
  Space space_;
  std::vector<float> clipped_;
};

}  // namespace rlrun
