#pragma once
// The joint action of a team of per-agent models (runtime/run/per_agent_training.hpp): agent
// a's column of a multi-agent env's observations goes through agent a's model, as each learner
// saw its own agent in training. Evaluation and recording run it like one model's ActionFn.
#include <functional>
#include <vector>

#include "rlrun/algos/algorithm.hpp"
#include "rlrun/env.hpp"
#include "rlrun/runtime/run/evaluator.hpp"

namespace rlrun {

// `models[a]` plays agent a of `env` (env.num_agents() == models.size()). A MaskablePPO model
// gets its own agent's mask of the env's Info (env/action_mask.hpp); a recurrent one keeps its
// own state, zeroed by `start_episode` (set here; call it after every reset, as
// model_action_fn's). The models outlive the ActionFn.
ActionFn team_action_fn(const std::vector<Algorithm*>& models, const Env& env, bool deterministic,
                        std::function<void()>* start_episode);

}  // namespace rlrun
