#pragma once
// What the two halves of SB3's VecNormalize (NormalizeObservation, NormalizeReward) share: a
// RunningMeanStd that the copies of a training VecEnv share and the model file keeps
// (model_statistics.hpp), SB3's training switch, batched mode (wrappers/vec_normalize.hpp: the
// VecEnv's hook does the work for the whole batch), and a step whose result after_step()
// transforms, whole or in two halves (env/split_step.hpp: forwarded, then this wrapper's work).
#include <memory>
#include <span>

#include "rlrun/env/split_step.hpp"
#include "rlrun/env/wrapper.hpp"
#include "rlrun/wrappers/model_statistics.hpp"
#include "rlrun/wrappers/running_mean_std.hpp"

namespace rlrun {

class RunningStatisticsWrapper : public Wrapper, public ModelStatistics, public SplitStep {
 public:
  StepResult step(std::span<const float> action, std::span<float> obs) override {
    return after_step(inner_->step(action, obs), obs);
  }
  bool steps_asynchronously() const override { return asynchronous_steps(*inner_) != nullptr; }
  void start_step(std::span<const float> action) override {
    asynchronous_steps(*inner_)->start_step(action);
  }
  StepResult finish_step(std::span<float> obs) override {
    return after_step(asynchronous_steps(*inner_)->finish_step(obs), obs);
  }

  void save_statistics(StateWriter& out) const override { rms_->write(out); }
  void load_statistics(const StateReader& in) override { rms_->read(in); }
  void set_training(bool training) override { training_ = training; }
  bool training() const override { return training_; }

  const RunningMeanStd& statistics() const { return *rms_; }
  // Batched mode: reset() and step() leave the statistics alone; the VecEnv's hook calls the
  // wrapper's batch functions.
  void set_batched(bool batched) { batched_ = batched; }
  bool steps_update_statistics() const override { return !batched_; }

 protected:
  explicit RunningStatisticsWrapper(EnvPtr inner) : Wrapper(std::move(inner)) {}
  // What step() does after the inner env stepped.
  virtual StepResult after_step(StepResult result, std::span<float> obs) = 0;

  std::shared_ptr<RunningMeanStd> rms_;  // set by the constructor
  bool training_ = true;
  bool batched_ = false;
};

}  // namespace rlrun
