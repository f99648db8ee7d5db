#pragma once
// ObservationTap: keeps a copy of the observation each step() returns, unchanged. The trainer
// puts it right above the Monitor of training env 0 when `obs_log` is on, so the observation
// log holds the env's own observations (what render_observation() can draw), not the
// normalised or stacked ones the policy sees. Not in the registry: runtime-internal.
#include <algorithm>
#include <vector>

#include "rlrun/env/split_step.hpp"
#include "rlrun/env/wrapper.hpp"

namespace rlrun {

class ObservationTap : public Wrapper, public SplitStep {
 public:
  // Observations and actions pass unchanged (rlrun export).
  bool exports_unchanged() const override { return true; }
  explicit ObservationTap(EnvPtr inner)
      : Wrapper(std::move(inner)), last_(inner_->observation_space().flat_dim(), 0.0f) {}

  StepResult step(std::span<const float> action, std::span<float> obs) override {
    const StepResult result = inner_->step(action, obs);
    std::copy(obs.begin(), obs.end(), last_.begin());
    return result;
  }

  bool steps_asynchronously() const override { return asynchronous_steps(*inner_) != nullptr; }
  void start_step(std::span<const float> action) override {
    asynchronous_steps(*inner_)->start_step(action);
  }
  StepResult finish_step(std::span<float> obs) override {
    const StepResult result = asynchronous_steps(*inner_)->finish_step(obs);
    std::copy(obs.begin(), obs.end(), last_.begin());
    return result;
  }

  // The observation the last step() returned (the final one when that step ended an episode).
  std::span<const float> last_step_obs() const { return last_; }

 private:
  std::vector<float> last_;
};

}  // namespace rlrun
