#pragma once
// Training callbacks (SB3 stable_baselines3/common/callbacks.py), each configured by a YAML
// section: eval (EvalCallback + StopTrainingOnRewardThreshold +
// StopTrainingOnNoModelImprovement), checkpoint (CheckpointCallback), obs_log (the course's
// ObsSaveCallback). The trainer calls every callback after every VecEnv step of every
// algorithm (TrainingHooks::on_step), with num_timesteps = total env steps over all envs.
// Frequencies in rlrun count those TOTAL steps (SB3's count calls, i.e. per-env steps).
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "rlrun/algos/algorithm.hpp"
#include "rlrun/core/logger.hpp"
#include "rlrun/env/vec_env.hpp"
#include "rlrun/runtime/components/registry.hpp"
#include "rlrun/runtime/experiment/env_spec.hpp"

namespace rlrun {

// One evaluation as evaluations.csv holds it (timesteps, then column -> value; a column left
// empty in the file is absent here). `rlrun tune` reports these to its pruner.
struct EvaluationRow {
  int64_t timesteps = 0;
  std::map<std::string, double> values;
};
// Called after each evaluation; a non-empty result stops training with that reason (a pruned
// trial).
using EvaluationListener = std::function<std::string(const EvaluationRow&)>;

// What callbacks may use; owned by the trainer, alive for the whole training. Each callback
// gets its own section's config besides (run/training_callbacks.hpp), not the experiment.
struct TrainingContext {
  const EnvSpec& env_spec;  // the training envs' spec: callbacks build their own copies from it
  uint64_t seed;            // run.seed: env i is seeded seed + i, a callback's envs after those
  const Registry& registry;
  std::string run_dir;
  Algorithm& algorithm;
  VecEnv& env;                                      // the training envs
  Logger* logger = nullptr;                         // records land in the next progress.csv row
  std::function<void(const std::string&)> message;  // a line on the console and in log.txt
  // A model file (with wrapper statistics) of that name in the run directory (best_model.zip).
  std::function<void(const std::string&)> save_model;
  // A checkpoint of that name in <run_dir>/checkpoints (step_<N>.zip).
  std::function<void(const std::string&)> save_checkpoint;
  bool resuming = false;  // continuing a run: append to its files, do not start them anew
  EvaluationListener on_evaluation;  // optional: told of every evaluation (EvalCallback)
  // A new algorithm of the run's configuration (self-play rebuilds its snapshots from their
  // saved model tensors in one).
  std::function<std::unique_ptr<Algorithm>()> make_algorithm;
};

class Callback {
 public:
  virtual ~Callback() = default;
  // After every VecEnv step; false stops training (SB3's callback.on_step()).
  virtual bool on_step(int64_t num_timesteps) = 0;
  // At each point where training can stop and resume exactly (TrainingHooks::at_safe_point:
  // after each PPO/A2C iteration, after each off-policy collect-and-train round).
  virtual void at_safe_point(int64_t /*num_timesteps*/) {}
  // Where SB3 calls callback.on_rollout_end() (TrainingHooks::on_rollout_end): after a
  // rollout, before the update that learns from it.
  virtual void on_rollout_end(int64_t /*num_timesteps*/) {}
  // Once after training ends, also after an early stop or Ctrl-C (SB3 on_training_end).
  // `resumable`: training stopped at a safe point that a checkpoint holds (Ctrl-C), so work
  // in progress belongs in that checkpoint, not in files.
  virtual void on_training_end(int64_t /*num_timesteps*/, bool /*resumable*/) {}

  // Exact resume: what decides when the callback fires next (written into checkpoints).
  virtual void write_state(StateWriter& /*out*/) const {}
  virtual void read_state(const StateReader& /*in*/) {}
  // Before a checkpoint: write buffered file output, so that the run's files end where the
  // checkpoint's state does.
  virtual void flush() {}
  // Why on_step() returned false (empty while training goes on).
  const std::string& stop_reason() const { return stop_reason_; }

 protected:
  std::string stop_reason_;
};

// True when num_timesteps reached `next`; then advances `next` past num_timesteps in steps of
// `freq` (one trigger even if a step of n_envs crossed several multiples).
inline bool crossed(int64_t num_timesteps, int64_t freq, int64_t& next) {
  if (freq <= 0 || num_timesteps < next) return false;
  while (next <= num_timesteps) next += freq;
  return true;
}

}  // namespace rlrun
