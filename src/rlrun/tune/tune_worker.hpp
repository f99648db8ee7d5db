#pragma once
// One `rlrun tune` worker: takes trials from the study journal until the study has its
// n_trials (over all workers), the worker's timeout passes, or Ctrl-C.
//
// Taking a trial (under the journal lock, tune/journal_storage.hpp Transaction):
//   1. RUNNING trials whose rlrun worker is gone (tune/worker_liveness.hpp) are marked FAIL with
//      system attribute rlrun:requeued and their parameters enqueued again (a WAITING trial
//      with fixed_params, rlrun:retry_of = the old number): a killed trial is neither lost nor
//      counted twice;
//   2. a WAITING trial (enqueued by Optuna's study.enqueue_trial, or re-queued) is taken first;
//   3. else a new trial is created while the trials that count (every trial but the re-queued
//      failures) number fewer than n_trials.
// Running a trial: the space samples its parameters (tune/trial.hpp), each seed trains in this
// process (runtime/run/trainer.hpp) into <out_dir>/trials/trial_<N>/seed<S>; every evaluation is
// reported (step = seed index * evaluations per seed + k, k from 1, as rl-zoo's
// TrialEvalCallback counts) and the pruner may stop the trial (PRUNED, with the last value).
// The trial's value is the objective's per-seed value (last/best/mean of its column) averaged
// over the seeds; a training failure, a config the space made invalid or a NaN value makes the
// trial FAIL (system attribute fail_reason) and the study goes on. Ctrl-C stops the running
// trial, re-queues it and ends the worker.
#include <cstdint>
#include <string>

#include "rlrun/core/execution_context.hpp"
#include "rlrun/tune/study_config.hpp"

namespace rlrun {
class Registry;
}

namespace rlrun::tune {

struct WorkerSummary {
  int complete = 0;
  int pruned = 0;
  int failed = 0;
  bool interrupted = false;
};

// `verbose`: show each seed's training output (else only the trial lines; log.txt has it all).
// `execution`: the threads each trial's training uses.
WorkerSummary run_worker(const StudyConfig& study, Registry& registry,
                         const ExecutionContext& execution, bool verbose = false);

// The trials that count towards n_trials: all but the FAIL ones marked rlrun:requeued.
int counted_trials(const std::vector<FrozenTrial>& trials);

}  // namespace rlrun::tune
