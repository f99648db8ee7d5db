#pragma once
// What a trial varies: a study file's `space:`, either `zoo` (rl-zoo's search space for the base
// experiment's algorithm, tune/zoo_spaces.hpp) or parameters written out:
//
//   space:
//     algo.learning_rate: {float: [1.0e-5, 1.0e-2], log: true}
//     algo.n_epochs: {int: [1, 20]}                        # step: 2 for every other value
//     algo.clip_range: {float: [0.1, 0.4], step: 0.1}
//     algo.policy.net_arch: {categorical: [[64], [64, 64], [256, 256]]}
//     algo.policy.activation_fn: {categorical: [tanh, relu]}
//     algo.ent_coef: {float: [1.0e-8, 0.1], log: true, if: {algo.policy.activation_fn: relu}}
//
// Each key is an experiment key (what `--set` takes) and the Optuna parameter's name. `if:`
// makes a parameter conditional: sampled only when the named parameters (earlier in the list)
// took one of the given values (a value or a list of values), else left at the base
// experiment's value — Optuna then sees a trial without it, as with a Python `if`.
// Categorical choices that are lists or maps (net_arch) are stored in the study as their YAML
// text ("[64, 64]"): Optuna's choices are scalars.
#include <memory>
#include <string>

#include "rlrun/core/config_node.hpp"
#include "rlrun/tune/study_space.hpp"

namespace rlrun::tune {

// `space:` of a study file: "zoo" (with the base experiment's algorithm id and whether it uses
// HER) or a map of parameters. ConfigError at the offending line for a bad entry.
std::unique_ptr<StudySpace> parse_space(const ConfigNode& node, const std::string& algo_id,
                                        bool uses_her);

}  // namespace rlrun::tune
