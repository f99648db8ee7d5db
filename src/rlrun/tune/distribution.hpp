#pragma once
// Optuna's three parameter distributions (optuna/distributions.py, Optuna 3.1), with the same
// JSON text (distribution_to_json / json_to_distribution) so that a study rlrun writes is an
// Optuna study, and the same "internal representation": the number a sampler works with —
// the value itself for float and int parameters, the index of the choice for categorical ones.
//
// A study file may come from anyone (docs/security.md): distribution_from_json checks every
// field and throws ConfigError, never trusts sizes or types.
#include <cstdint>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include <nlohmann/json.hpp>

namespace rlrun::tune {

// suggest_float(low, high, log=..., step=...): `step` and `log` exclude each other.
struct FloatDistribution {
  double low = 0;
  double high = 0;
  bool log = false;
  std::optional<double> step;
  bool operator==(const FloatDistribution&) const = default;
};

// suggest_int(low, high, log=..., step=...).
struct IntDistribution {
  int64_t low = 0;
  int64_t high = 0;
  bool log = false;
  int64_t step = 1;
  bool operator==(const IntDistribution&) const = default;
};

// suggest_categorical(choices): each choice is null, a bool, an int, a float or a string, as
// in Optuna (CategoricalChoiceType). The internal representation is the index.
struct CategoricalDistribution {
  std::vector<nlohmann::json> choices;
  bool operator==(const CategoricalDistribution&) const = default;
};

using Distribution = std::variant<FloatDistribution, IntDistribution, CategoricalDistribution>;

// Whether the distribution is sampled on a log scale (`log: true`; Optuna's `log` flag).
inline bool is_log_scale(const Distribution& d) {
  if (const auto* f = std::get_if<FloatDistribution>(&d)) return f->log;
  if (const auto* i = std::get_if<IntDistribution>(&d)) return i->log;
  return false;
}

// The constructors' checks and adjustments as Optuna's: low <= high, log needs low > 0, step >
// 0, log and step not together, high moved down onto the step grid (Optuna warns; rlrun too,
// in the caller's words). Throw ConfigError with `what` (the parameter's name) in the message.
FloatDistribution make_float_distribution(const std::string& what, double low, double high,
                                          bool log, std::optional<double> step);
IntDistribution make_int_distribution(const std::string& what, int64_t low, int64_t high, bool log,
                                      int64_t step);
CategoricalDistribution make_categorical_distribution(const std::string& what,
                                                      std::vector<nlohmann::json> choices);

// Optuna's distribution_to_json: {"name": "FloatDistribution", "attributes": {...}} as text.
std::string distribution_to_json(const Distribution& distribution);
// Optuna's json_to_distribution, both the full and the abbreviated ({"type": "float", ...})
// form; checks what it reads (ConfigError naming `origin`).
Distribution distribution_from_json(const std::string& text, const std::string& origin);

// Optuna's BaseDistribution.single(): only one value is possible.
bool single(const Distribution& distribution);
// _contains(internal value).
bool contains(const Distribution& distribution, double internal);
// to_external_repr: the value a trial's params show (a JSON number, or the choice).
nlohmann::json to_external(const Distribution& distribution, double internal);
// to_internal_repr: a value as Optuna stores it; throws ConfigError for a value that is not
// one of the choices or not a number.
double to_internal(const Distribution& distribution, const nlohmann::json& external);
// Optuna's check_distribution_compatibility: same kind; categorical with the same choices.
bool compatible(const Distribution& a, const Distribution& b);

}  // namespace rlrun::tune
