#pragma once
// Runs one experiment end to end: run directory, resolved config.yaml, envs with monitor
// files, the algorithm, logging (progress.csv, console, log.txt), the callbacks the config
// turns on (runtime/run/callback.hpp: eval, checkpoint, obs_log, video), and model.zip at the end,
// after an early stop or on Ctrl-C. Model files hold the normalisation statistics.
//
// Exact resume (`rlrun train --resume`): a checkpoint (checkpoints/step_<N>.zip) holds, beside
// the model, the training state — the algorithm's counters, optimizer moments, RNG streams and
// replay buffer, every env's state with its wrappers (normalisation statistics, Monitor
// counters), the callbacks' counters, the logger's pending values and how far each CSV file had
// got. Resuming cuts the files back to the checkpoint and continues: the weights, progress.csv
// and monitor files end as those of the uninterrupted run.
//
// One process trains a run directory at a time (runtime/io/run_lock.hpp).
//
// Ctrl-C (SIGINT/SIGTERM, core/interrupt.hpp) asks training to stop at the next safe point (after the current
// PPO/A2C update or off-policy round), where a checkpoint is written; a second Ctrl-C stops at
// the next env step without one. A NaN or inf in a loss or a parameter stops the run with a
// RuntimeFailure naming the step and the quantity; nothing non-finite is ever saved.
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "rlrun/core/execution_context.hpp"
#include "rlrun/runtime/experiment/experiment.hpp"
#include "rlrun/runtime/run/callback.hpp"
#include "rlrun/runtime/run/train_outcome.hpp"

namespace rlrun {

// `resume_from` non-empty: continue the run these checkpoints belong to (newest first, as
// runtime/run/resume_point.hpp lists them; a damaged one is skipped with a note), with
// `experiment` loaded from that run's config.yaml.
// `on_evaluation`: told of every evaluation; may stop training (runtime/run/callback.hpp).
// `execution`: the threads the run uses (its results are the same with any number).
TrainOutcome train_experiment(const Experiment& experiment, const Registry& registry,
                              const ExecutionContext& execution,
                              const std::vector<std::string>& resume_from = {},
                              EvaluationListener on_evaluation = {});

// A training that goes on over several learn() calls in one process: SB3's model.learn() as
// the Python API offers it (python/rlrun/_algorithms.py). The run directory, envs, algorithm
// (optimizer moments, replay buffer, RNG streams) and the config's callbacks live from the
// constructor to the destructor; each learn() trains until the run's total env steps reach
// its argument and ends as train_experiment does (model.zip, summary line, `finished`).
class TrainingSession {
 public:
  TrainingSession(Experiment experiment, const Registry& registry,
                  const ExecutionContext& execution);
  ~TrainingSession();
  TrainingSession(const TrainingSession&) = delete;
  TrainingSession& operator=(const TrainingSession&) = delete;

  // `extra`: the caller's callbacks (built on context()), told of this learn() only.
  // `log_interval`: SB3's learn(log_interval=...) for this call (run.log_interval's meaning);
  // unset keeps the experiment's.
  TrainOutcome learn(int64_t total_timesteps,
                     const std::vector<std::unique_ptr<Callback>>& extra = {},
                     std::optional<int> log_interval = std::nullopt);
  TrainingContext& context();
  int64_t num_timesteps() const;
  const Experiment& experiment() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace rlrun
