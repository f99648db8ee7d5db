#pragma once
// A wrapper that changes only the actions (Gymnasium's ActionWrapper,
// gymnasium/core.py): the agent acts in action_space(), map_action() turns each action into
// the inner env's, and the observations pass unchanged. The two halves of step()
// (env/split_step.hpp) hand the mapped action on, so a stack of them on an env that steps in
// another process still steps asynchronously. ClipAction and RescaleAction are two.
#include <span>
#include <string>

#include "rlrun/env/split_step.hpp"
#include "rlrun/env/wrapper.hpp"

namespace rlrun {

class ActionWrapper : public Wrapper, public SplitStep {
 public:
  const Space& action_space() const override { return space_; }
  StepResult step(std::span<const float> action, std::span<float> obs) override {
    return inner_->step(map_action(action), obs);
  }
  bool steps_asynchronously() const override { return asynchronous_steps(*inner_) != nullptr; }
  void start_step(std::span<const float> action) override {
    asynchronous_steps(*inner_)->start_step(map_action(action));
  }
  StepResult finish_step(std::span<float> obs) override {
    return asynchronous_steps(*inner_)->finish_step(obs);
  }

  std::string export_observation(PolicyGraph& /*graph*/, const std::string& obs) const override {
    return obs;
  }

 protected:
  explicit ActionWrapper(EnvPtr inner) : Wrapper(std::move(inner)) {}
  // The inner env's action for the agent's `action`; valid until the next call.
  virtual std::span<const float> map_action(std::span<const float> action) = 0;

  Space space_;  // the agent's action space, set by the constructor
};

}  // namespace rlrun
