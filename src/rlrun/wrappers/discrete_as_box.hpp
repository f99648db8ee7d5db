#pragma once
// Lets a Box-action algorithm (SAC, TD3, DDPG) drive a Discrete(n) env: the policy outputs
// one score per discrete action in Box(-1, 1, (n,)) and the env receives the argmax (first
// maximum on ties). Used by `env.auto_wrap: true` or `wrappers: [{id: DiscreteAsBox}]`.
#include "rlrun/env/wrapper.hpp"
#include "rlrun/wrappers/no_options.hpp"

namespace rlrun {

class DiscreteAsBox : public Wrapper {
 public:
  using Config = NoOptions;
  // Throws std::invalid_argument when the inner action space is not Discrete.
  DiscreteAsBox(EnvPtr inner, const Config& config);
  explicit DiscreteAsBox(EnvPtr inner) : DiscreteAsBox(std::move(inner), Config()) {}
  const Space& action_space() const override { return space_; }
  StepResult step(std::span<const float> action, std::span<float> obs) override;
  std::string export_observation(PolicyGraph& /*graph*/, const std::string& obs) const override {
    return obs;
  }
  std::string export_action(PolicyGraph& graph, const std::string& action) const override;

 private:
  Space space_;
  float discrete_action_ = 0.0f;
};

}  // namespace rlrun
