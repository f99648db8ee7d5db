#pragma once
// SB3's evaluate_policy (stable_baselines3/common/evaluation.py) for one env: runs n episodes
// with the algorithm's predict(), the first reset seeded, and reports the Monitor's episode
// returns (the env's true reward, before reward wrappers) when the env has a Monitor.
#include <cstdint>
#include <functional>
#include <optional>
#include <vector>

#include "rlrun/algos/algorithm.hpp"
#include "rlrun/env.hpp"
#include "rlrun/env/action_mask.hpp"

namespace rlrun {

// Maps the observations (obs_dim x agents: one column, or one per agent of a multi-agent env)
// to the actions (act_dim x agents); a trained model's predict() or a
// baseline such as the traffic task's fixed-time cycle.
using ActionFn = std::function<void(const Eigen::MatrixXf& obs, Eigen::MatrixXf& action)>;

struct EvalResult {
  std::vector<double> returns;
  std::vector<int64_t> lengths;
  std::vector<double> successes;  // one per episode where the env reports is_success
  // The env's own info values at each episode's end (its metrics, e.g. the traffic task's
  // avg_waiting_time), by key; Monitor/TimeLimit keys left out.
  std::vector<std::string> metric_keys;
  std::vector<std::vector<double>> metrics;  // [episode][key]

  double mean_return() const;
  double std_return() const;  // population std, as numpy's std in SB3
  double mean_length() const;
};

// A trained model's ActionFn for episodes of `env`: predict(), or predict_masked() with the
// masks `env` reports for its current state (env/action_mask.hpp) when the algorithm reads
// them (MaskablePPO's use_masking: sb3-contrib's evaluate_policy and MaskableEvalCallback pass
// get_action_masks(env) at every step). Call it right after env's reset() or step(), as
// evaluate_policy and record_episodes do. A missing, wrong-length or all-0 mask throws
// RuntimeFailure naming the env and the step.
// A recurrent model (Algorithm::recurrent_state_size() > 0, RecurrentPPO) carries its state
// from step to step and zeroes it where an episode starts (sb3-contrib's evaluate_policy passes
// episode_starts): `start_episode` then receives the hook to call after every reset()
// (std::logic_error when it is null).
// The action masks `env`'s Info holds for `agents` columns into `masks` (mask size x agents),
// read at the episodes' step `step`; a mask the env got wrong (no legal action, a missing
// entry) is a RuntimeFailure naming the env and the step.
void read_env_action_masks(ActionMaskReader& reader, const Env& env, int agents, int64_t step,
                           Eigen::MatrixXf& masks);

ActionFn model_action_fn(Algorithm& algorithm, const Env& env, bool deterministic,
                         std::function<void()>* start_episode = nullptr);

// evaluate_policy(model_action_fn(algorithm, env, deterministic, &start_episode), ...).
EvalResult evaluate_policy(Algorithm& algorithm, Env& env, int n_episodes, bool deterministic,
                           std::optional<uint64_t> seed);
// `start_episode` (may be empty) is called after each reset, before the episode's first action.
EvalResult evaluate_policy(const ActionFn& policy, Env& env, int n_episodes,
                           std::optional<uint64_t> seed,
                           const std::function<void()>& start_episode = {});

}  // namespace rlrun
