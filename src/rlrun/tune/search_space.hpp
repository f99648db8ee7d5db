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
#include <vector>

#include <nlohmann/json.hpp>

#include "rlrun/core/config_node.hpp"
#include "rlrun/tune/distribution.hpp"

namespace rlrun::tune {

// How a space asks the trial for values (tune/trial.hpp implements it over the sampler and the
// study journal). Returns the external value (a JSON number, or the choice).
class TrialSuggest {
 public:
  virtual ~TrialSuggest() = default;
  virtual nlohmann::json suggest(const std::string& name, const Distribution& distribution) = 0;
  virtual void set_user_attr(const std::string& key, const nlohmann::json& value) = 0;
};

// One experiment override ("algo.gamma" = "0.98" as YAML text), what `--set` takes.
struct Override {
  std::string key;
  std::string yaml;
  std::string assignment() const { return key + "=" + yaml; }
};

class StudySpace {
 public:
  virtual ~StudySpace() = default;
  // Samples a trial's parameters and turns them into overrides of the base experiment.
  virtual std::vector<Override> sample(TrialSuggest& trial) const = 0;
  // Overrides for parameters as a finished trial holds them ({name: external value}) — for
  // --best-config and --trial N; the same conversion as sample().
  virtual std::vector<Override> overrides_for(const nlohmann::json& params) const = 0;
  virtual std::string describe() const = 0;
};

// `space:` of a study file: "zoo" (with the base experiment's algorithm id and whether it uses
// HER) or a map of parameters. ConfigError at the offending line for a bad entry.
std::unique_ptr<StudySpace> parse_space(const ConfigNode& node, const std::string& algo_id,
                                        bool uses_her);

// A JSON value as YAML text for an override ("tanh", 0.001, [64, 64]).
std::string yaml_text_of(const nlohmann::json& value);

}  // namespace rlrun::tune
