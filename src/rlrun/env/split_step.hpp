#pragma once
// A step in two halves, SB3's VecEnv.step_async / step_wait
// (stable_baselines3/common/vec_env/base_vec_env.py): start_step() hands the action over and
// returns at once, finish_step() waits for the result. An env that steps in another process
// (a Python worker) implements it, and so do the wrappers that may sit on it (TimeLimit,
// Monitor, ObservationTap: they forward the halves and do their own work in finish_step), so
// that a VecEnv can start every copy's step before it waits for any: the workers run in
// parallel and rlrun wakes once per batch rather than once per env.
//
// A side interface (found by dynamic_cast) rather than part of rlrun::Env, so the plugin
// binary interface is unchanged; an env stack with any other wrapper in it steps whole.
#include <span>
#include <stdexcept>

#include "rlrun/env.hpp"

namespace rlrun {

class SplitStep {
 public:
  virtual ~SplitStep() = default;
  // True when start_step() really returns before the step is done (the env at the bottom of
  // the stack steps elsewhere and every wrapper on it forwards the halves).
  virtual bool steps_asynchronously() const = 0;
  // Exactly one finish_step() follows each start_step(), with nothing else called between.
  virtual void start_step(std::span<const float> action) = 0;
  virtual StepResult finish_step(std::span<float> obs) = 0;

  // Several agents (Env::step_agents in two halves: a TrafficNetwork's SUMO worker runs while
  // the other copies start). A stack splits its agents' steps only when every layer says so.
  virtual bool splits_agents() const { return false; }
  virtual void start_step_agents(std::span<const float> /*actions*/) {
    throw std::logic_error("this env does not step its agents in two halves");
  }
  virtual void finish_step_agents(std::span<float> /*obs*/, std::span<StepResult> /*results*/) {
    throw std::logic_error("this env does not step its agents in two halves");
  }
};

// The env's SplitStep when it steps asynchronously, else nullptr. For a multi-agent env, only
// when it also splits its agents' steps.
inline SplitStep* asynchronous_steps(Env& env) {
  auto* split = dynamic_cast<SplitStep*>(&env);
  if (!split || !split->steps_asynchronously()) return nullptr;
  return env.num_agents() == 1 || split->splits_agents() ? split : nullptr;
}

}  // namespace rlrun
