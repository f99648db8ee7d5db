#pragma once
// `rlrun eval --trajectory FILE.csv`: every step the env itself took during an evaluation,
// recorded right above the env (runtime/experiment/base_layer.hpp), below TimeLimit, Monitor and the
// model's wrappers — so the observation is the env's own (not normalised) and the action is
// the one the env received (after RescaleAction, ClipAction, ...). That is what a Gymnasium
// user of the bare env sees, and what the Python package's `model.predict` takes and returns
// (docs/python.md): the file lets tests check both against each other, bit for bit.
//
// One row per step:  episode,step,obs_0,...,obs_{d-1},[qpos_*,qvel_*,qacc_warmstart_*,]action_0,...,
// action_{k-1},reward,terminated,truncated — obs_i/action_i the flat float32 values (a Dict's keys in sorted
// order, a Discrete value as its integer) with 9 significant digits (core/float_format.hpp:
// float32 round-trips exactly), the observation being the one the action was chosen on;
// reward as Python's repr of the double; terminated/truncated 0 or 1 as the env returned them
// (a time limit's truncation happens above this layer: it shows as the episode's last row).
// Envs with a PhysicsState (the MuJoCo tasks) add the simulator state the action was applied
// to, qpos, qvel and the solver's warm start as Python's repr of the doubles: set_state(qpos,
// qvel), data.qacc_warmstart[:] = ..., then step(action) replays the row bit for bit in another
// implementation of the task (Gymnasium's, on the same MuJoCo).
#include <string>
#include <vector>

#include "rlrun/env/wrapper.hpp"

namespace rlrun {

class TrajectoryTap : public Wrapper {
 public:
  // Observations and actions pass unchanged (rlrun export).
  bool exports_unchanged() const override { return true; }
  explicit TrajectoryTap(EnvPtr env);

  void reset(std::optional<uint64_t> seed, std::span<float> obs) override;
  StepResult step(std::span<const float> action, std::span<float> obs) override;

  // The CSV text so far, header included.
  const std::string& csv() const { return csv_; }

 private:
  std::vector<float> obs_;  // the observation the next action is chosen on
  int64_t episode_ = -1;
  int64_t step_ = 0;
  std::string csv_;
};

// Puts a TrajectoryTap under `stack` (see runtime/experiment/base_layer.hpp) and returns it. Throws
// UsageError for a multi-agent env (one row per step holds one agent's values).
TrajectoryTap& tap_trajectory(Env& stack);

// Writes the tap's CSV to `path` (every write checked; RuntimeFailure names the file).
void write_trajectory(const TrajectoryTap& tap, const std::string& path);

}  // namespace rlrun
