#pragma once
// What a study varies, as the workers see it: a StudySpace samples a trial's parameters through
// TrialSuggest and turns them into experiment overrides. tune/search_space.hpp reads one from a
// study file, tune/zoo_spaces.hpp has rl-zoo's.
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

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

// A JSON value as YAML text for an override ("tanh", 0.001, [64, 64]).
std::string yaml_text_of(const nlohmann::json& value);

}  // namespace rlrun::tune
