#pragma once
// `env.agent_policies: per_agent`: one learner per agent of a multi-agent env (independent
// learners, each with its own networks and optimiser), as RLlib's policy-per-agent mapping or
// one SB3 model per agent of a PettingZoo parallel env give; the default `shared` trains one
// policy on every agent's experience (parameter sharing, env/vec_env.hpp).
//
// The run directory `<out_dir>/<name>/seed<N>/` holds the experiment's config.yaml, log.txt and
// agents.json (the team: each agent's name and run directory), and under agents/ one complete
// run directory per agent (`agents/<agent>/seed<N + i>/`: config.yaml, progress.csv, monitor
// files, evaluations, checkpoints, model.zip), trained by the experiment as written: the
// learners run on threads of their own and meet at every env step (env/agent_seats.hpp).
// Agent i's learner is seeded seed + i (its networks and its sampling); the envs are seeded
// from the run's seed, as a shared-policy run seeds them. `rlrun eval --model <run dir>` plays
// the whole team (runtime/io/agent_team_file.hpp).
#include <functional>
#include <string>
#include <vector>

#include "rlrun/core/execution_context.hpp"
#include "rlrun/runtime/experiment/experiment.hpp"
#include "rlrun/runtime/run/callback.hpp"
#include "rlrun/runtime/run/train_outcome.hpp"

namespace rlrun {

// Trains one learner's experiment: train_experiment's single-run path.
using TrainOneLearner = std::function<TrainOutcome(
    const Experiment& experiment, const Registry& registry, const ExecutionContext& execution,
    EvaluationListener on_evaluation)>;

// Trains `experiment` (its env.agent_policies is per_agent) with one learner per agent, each
// through `train_one`. `on_evaluation` (rlrun tune) hears agent 0's evaluations. The run's
// threads are divided among the learners (at least one each). A per-agent run cannot be
// resumed: its learners' checkpoints hold their models only.
TrainOutcome train_per_agent(const Experiment& experiment, const Registry& registry,
                             const ExecutionContext& execution, EvaluationListener on_evaluation,
                             const TrainOneLearner& train_one);

}  // namespace rlrun
