#pragma once
// TimeLimit: gymnasium/wrappers/common.py. Counts steps since the last reset() and reports
// truncated = true once elapsed >= max_episode_steps. `terminated` passes through untouched,
// so a terminal step on the last allowed step reports both flags, as Gymnasium does.
#include <optional>
#include <span>

#include "rlrun/env/split_step.hpp"
#include "rlrun/env/wrapper.hpp"

namespace rlrun {

class TimeLimit : public Wrapper, public SplitStep {
 public:
  // Observations and actions pass unchanged (rlrun export).
  bool exports_unchanged() const override { return true; }
  // Throws std::invalid_argument unless max_episode_steps > 0 (Gymnasium asserts it).
  TimeLimit(EnvPtr inner, int max_episode_steps);

  void reset(std::optional<uint64_t> seed, std::span<float> obs) override;
  StepResult step(std::span<const float> action, std::span<float> obs) override;
  void step_agents(std::span<const float> actions, std::span<float> obs,
                   std::span<StepResult> results) override;

  // The two halves of step() (env/split_step.hpp), forwarded to the inner env.
  bool steps_asynchronously() const override { return asynchronous_steps(*inner_) != nullptr; }
  void start_step(std::span<const float> action) override {
    asynchronous_steps(*inner_)->start_step(action);
  }
  StepResult finish_step(std::span<float> obs) override {
    return count_step(asynchronous_steps(*inner_)->finish_step(obs));
  }
  bool splits_agents() const override { return asynchronous_steps(*inner_) != nullptr; }
  void start_step_agents(std::span<const float> actions) override {
    asynchronous_steps(*inner_)->start_step_agents(actions);
  }
  void finish_step_agents(std::span<float> obs, std::span<StepResult> results) override {
    asynchronous_steps(*inner_)->finish_step_agents(obs, results);
    count_agents(results);
  }

  int max_episode_steps() const { return max_episode_steps_; }
  // Steps taken since the last reset().
  int elapsed_steps() const { return elapsed_steps_; }

 protected:
  void write_own_state(StateWriter& out) const override {
    out.put_int("time_limit/elapsed_steps", elapsed_steps_);
  }
  void read_own_state(const StateReader& in) override {
    elapsed_steps_ = static_cast<int>(in.get_count("time_limit/elapsed_steps", max_episode_steps_));
  }

 private:
  StepResult count_step(StepResult result) {
    ++elapsed_steps_;
    if (elapsed_steps_ >= max_episode_steps_) result.truncated = true;
    return result;
  }

  // Every agent is truncated at the limit (Gymnasium's TimeLimit truncates the whole env).
  void count_agents(std::span<StepResult> results) {
    ++elapsed_steps_;
    if (elapsed_steps_ >= max_episode_steps_)
      for (StepResult& r : results) r.truncated = true;
  }

  int max_episode_steps_;
  int elapsed_steps_ = 0;
};

}  // namespace rlrun
