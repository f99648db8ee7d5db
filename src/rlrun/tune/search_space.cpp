#include "rlrun/tune/search_space.hpp"

#include <yaml-cpp/yaml.h>

#include <cmath>
#include <map>
#include <optional>
#include <regex>

#include "rlrun/core/errors.hpp"
#include "rlrun/tune/zoo_spaces.hpp"

namespace rlrun::tune {
namespace {

// A YAML scalar as the JSON value Optuna would hold: integers, floats, booleans and null as
// YAML 1.2's core schema reads them; quoted or other text as a string.
nlohmann::json scalar_json(const YAML::Node& node) {
  const std::string& text = node.Scalar();
  if (node.Tag() == "!") return text;  // quoted: always a string
  static const std::regex integer("[-+]?[0-9]+");
  static const std::regex floating("[-+]?(\\.[0-9]+|[0-9]+(\\.[0-9]*)?)([eE][-+]?[0-9]+)?");
  if (std::regex_match(text, integer)) {
    try {
      return std::stoll(text);
    } catch (...) {
    }
  }
  if (std::regex_match(text, floating)) return std::stod(text);
  if (text == "true" || text == "True" || text == "TRUE") return true;
  if (text == "false" || text == "False" || text == "FALSE") return false;
  if (text == "null" || text == "Null" || text == "NULL" || text == "~" || text.empty())
    return nullptr;
  return text;
}

// Optuna's equality of choices: True == 1 == 1.0.
bool same_value(const nlohmann::json& a, const nlohmann::json& b) {
  if (a.is_number() && b.is_number()) return a.get<double>() == b.get<double>();
  return a == b;
}

struct Condition {
  std::string parameter;
  std::vector<nlohmann::json> values;
};

struct Parameter {
  std::string key;
  Distribution distribution;
  bool yaml_choices = false;  // categorical choices stored as YAML text
  std::vector<Condition> conditions;
};

class ExplicitSpace : public StudySpace {
 public:
  explicit ExplicitSpace(std::vector<Parameter> parameters) : parameters_(std::move(parameters)) {}

  std::vector<Override> sample(TrialSuggest& trial) const override {
    std::map<std::string, nlohmann::json> chosen;
    std::vector<Override> out;
    for (const Parameter& p : parameters_) {
      if (!conditions_hold(p, chosen)) continue;
      const nlohmann::json value = trial.suggest(p.key, p.distribution);
      chosen[p.key] = value;
      out.push_back(override_of(p, value));
    }
    return out;
  }

  std::vector<Override> overrides_for(const nlohmann::json& params) const override {
    std::vector<Override> out;
    for (const Parameter& p : parameters_)
      if (params.contains(p.key)) out.push_back(override_of(p, params[p.key]));
    return out;
  }

  std::string describe() const override {
    return std::to_string(parameters_.size()) + " parameters from the study file";
  }

 private:
  static bool conditions_hold(const Parameter& p,
                              const std::map<std::string, nlohmann::json>& chosen) {
    for (const Condition& c : p.conditions) {
      auto it = chosen.find(c.parameter);
      if (it == chosen.end()) return false;
      bool any = false;
      for (const auto& v : c.values) any = any || same_value(v, it->second);
      if (!any) return false;
    }
    return true;
  }

  static Override override_of(const Parameter& p, const nlohmann::json& value) {
    if (p.yaml_choices && value.is_string()) return {p.key, value.get<std::string>()};
    return {p.key, yaml_text_of(value)};
  }

  std::vector<Parameter> parameters_;
};

double number_of(const ConfigNode& n) { return n.as_double(); }

// The keys of one parameter's map: known ones, and exactly one kind.
void check_parameter_keys(const ConfigNode& spec) {
  if (!spec.is_map())
    spec.fail(
        "a parameter is a map: {float: [low, high]}, {int: [low, high]} or {categorical: [...]}, "
        "with log, step and if as options");
  static const std::vector<std::string> kKeys{"float", "int", "categorical", "log", "step", "if"};
  int kinds = 0;
  for (const std::string& k : spec.keys()) {
    if (std::find(kKeys.begin(), kKeys.end(), k) == kKeys.end())
      spec.fail_at_key(k, "unknown key '" + k + "'" + did_you_mean(k, kKeys) +
                              "; a parameter has float, int or categorical, and log, step, if");
    if (k == "float" || k == "int" || k == "categorical") ++kinds;
  }
  if (kinds != 1)
    spec.fail(
        "a parameter has exactly one of float: [low, high], int: [low, high], categorical: [...]");
}

// categorical: [...]; a choice that is a map or a list is passed on as YAML text.
void parse_categorical(const std::string& key, const ConfigNode& spec, Parameter& p) {
  const ConfigNode choices = spec.child("categorical");
  if (!choices.is_sequence() || choices.size() == 0)
    choices.fail("expected a non-empty list of choices");
  if (spec.has("log") || spec.has("step"))
    spec.fail("log and step are for float and int parameters");
  std::vector<nlohmann::json> values;
  for (size_t i = 0; i < choices.size(); ++i) {
    // A copy (a handle into the same document): yaml() is a reference into the ConfigNode
    // at(i) returns, which ends with this statement (ASan: stack-use-after-scope).
    const YAML::Node c = choices.at(i).yaml();
    if (c.IsScalar() || c.IsNull()) {
      values.push_back(c.IsNull() ? nlohmann::json(nullptr) : scalar_json(c));
    } else {
      values.push_back(yaml_override_text(c));
      p.yaml_choices = true;
    }
  }
  p.distribution = make_categorical_distribution(key, values);
}

// float: [low, high] or int: [low, high], with log and step.
void parse_range(const std::string& key, const ConfigNode& spec, Parameter& p) {
  const bool log = spec.has("log") && spec.child("log").as_bool();
  const bool is_float = spec.has("float");
  const ConfigNode range = spec.child(is_float ? "float" : "int");
  if (!range.is_sequence() || range.size() != 2) range.fail("expected [low, high]");
  if (is_float) {
    std::optional<double> step;
    if (spec.has("step")) step = number_of(spec.child("step"));
    p.distribution =
        make_float_distribution(key, number_of(range.at(0)), number_of(range.at(1)), log, step);
  } else {
    const int64_t step = spec.has("step") ? spec.child("step").as_int() : 1;
    p.distribution =
        make_int_distribution(key, range.at(0).as_int(), range.at(1).as_int(), log, step);
  }
}

// if: {parameter: value or [values]}, naming only parameters listed before this one.
void parse_conditions(const ConfigNode& spec, const std::vector<Parameter>& earlier, Parameter& p) {
  const ConfigNode cond = spec.child("if");
  if (!cond.is_map() || cond.size() == 0) cond.fail("expected {parameter: value or [values]}");
  for (const std::string& name : cond.keys()) {
    const bool known = std::any_of(earlier.begin(), earlier.end(),
                                   [&](const Parameter& e) { return e.key == name; });
    if (!known) {
      std::vector<std::string> names;
      for (const auto& e : earlier) names.push_back(e.key);
      cond.fail_at_key(name, "'" + name + "' is not a parameter listed before this one" +
                                 did_you_mean(name, names));
    }
    Condition c{name, {}};
    const ConfigNode values = cond.child(name);
    if (values.is_sequence()) {
      for (size_t i = 0; i < values.size(); ++i)
        c.values.push_back(scalar_json(values.at(i).yaml()));
    } else {
      c.values.push_back(scalar_json(values.yaml()));
    }
    p.conditions.push_back(c);
  }
}

Parameter parse_parameter(const std::string& key, const ConfigNode& spec,
                          const std::vector<Parameter>& earlier) {
  check_parameter_keys(spec);
  Parameter p;
  p.key = key;
  try {
    if (spec.has("categorical"))
      parse_categorical(key, spec, p);
    else
      parse_range(key, spec, p);
  } catch (const ConfigError& e) {
    // A value's own error already names its position; the distribution's checks do not.
    if (std::string(e.what()).rfind(spec.origin() + ":", 0) == 0) throw;
    spec.fail(e.what());
  }
  if (spec.has("if")) parse_conditions(spec, earlier, p);
  return p;
}

}  // namespace

std::unique_ptr<StudySpace> parse_space(const ConfigNode& node, const std::string& algo_id,
                                        bool uses_her) {
  if (!node.defined()) node.fail("space: missing (zoo, or a map of parameters)");
  if (node.is_scalar()) {
    if (node.as_string() != "zoo") node.fail("space: expected zoo or a map of parameters");
    try {
      return zoo_space(algo_id, uses_her);
    } catch (const UsageError& e) {
      node.fail(e.what());
    }
  }
  if (!node.is_map() || node.size() == 0) node.fail("space: expected zoo or a map of parameters");
  std::vector<Parameter> parameters;
  for (const std::string& key : node.keys())
    parameters.push_back(parse_parameter(key, node.child(key), parameters));
  return std::make_unique<ExplicitSpace>(std::move(parameters));
}

}  // namespace rlrun::tune
