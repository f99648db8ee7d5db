#include "rlrun/tune/distribution.hpp"

#include <charconv>
#include <cmath>
#include <cstdlib>

#include "rlrun/core/errors.hpp"

namespace rlrun::tune {
namespace {

// The number of decimal places of a double's shortest round-trip text ("0.25" -> 2,
// "1e-05" -> 5, "300" -> 0), or -1 past 15 (no exact decimal arithmetic then).
int decimal_places(double x) {
  char text[64];
  auto [end, error] = std::to_chars(text, text + sizeof text, x, std::chars_format::scientific);
  if (error != std::errc()) return -1;
  std::string s(text, end);  // d.ddde[+-]XX
  size_t e = s.find('e');
  std::string mantissa = s.substr(0, e);
  int exponent = std::atoi(s.c_str() + e + 1);
  size_t dot = mantissa.find('.');
  int fraction_digits = dot == std::string::npos ? 0 : static_cast<int>(mantissa.size() - dot - 1);
  int places = fraction_digits - exponent;
  if (places < 0) places = 0;
  return places > 15 ? -1 : places;
}

// Optuna's _adjust_discrete_uniform_high, which works in decimal.Decimal(str(x)): the range
// must be a whole number of steps, else high moves down onto the grid. Decimal arithmetic is
// reproduced exactly with integers scaled by 10^places (0.1 to 1.0 in steps of 0.1 stays 1.0).
double adjust_float_high(double low, double high, double step) {
  int places = std::max({decimal_places(low), decimal_places(high), decimal_places(step)});
  bool exact = decimal_places(low) >= 0 && decimal_places(high) >= 0 && decimal_places(step) >= 0;
  double scale = std::pow(10.0, places);
  if (exact && std::fabs(high) * scale < 9e15 && std::fabs(low) * scale < 9e15) {
    auto l = static_cast<int64_t>(std::llround(low * scale));
    auto h = static_cast<int64_t>(std::llround(high * scale));
    auto s = static_cast<int64_t>(std::llround(step * scale));
    if (s > 0 && (h - l) % s != 0) return static_cast<double>((h - l) / s * s + l) / scale;
    return high;
  }
  double n = std::floor((high - low) / step);
  double adjusted = n * step + low;
  return adjusted < high ? adjusted : high;
}

[[noreturn]] void fail(const std::string& what, const std::string& message) {
  throw ConfigError(what + ": " + message);
}

bool is_choice_type(const nlohmann::json& v) {
  return v.is_null() || v.is_boolean() || v.is_number() || v.is_string();
}

// Optuna compares choices with ==, where True == 1 and 1 == 1.0.
bool same_choice(const nlohmann::json& a, const nlohmann::json& b) {
  auto numeric = [](const nlohmann::json& v, double& out) {
    if (v.is_boolean())
      out = v.get<bool>() ? 1.0 : 0.0;
    else if (v.is_number())
      out = v.get<double>();
    else
      return false;
    return true;
  };
  double x = 0, y = 0;
  if (numeric(a, x) && numeric(b, y)) return x == y;
  return a == b;
}

}  // namespace

FloatDistribution make_float_distribution(const std::string& what, double low, double high,
                                          bool log, std::optional<double> step) {
  if (!std::isfinite(low) || !std::isfinite(high)) fail(what, "low and high must be finite");
  if (low > high)
    fail(what, "low must be <= high (low=" + std::to_string(low) +
                   ", high=" + std::to_string(high) + ")");
  if (log && step) fail(what, "`step` and `log` cannot be used together (as in Optuna)");
  if (log && low <= 0) fail(what, "a log distribution needs low > 0");
  if (step && !(*step > 0 && std::isfinite(*step))) fail(what, "step must be > 0");
  FloatDistribution d{low, high, log, step};
  if (step) d.high = adjust_float_high(low, high, *step);
  return d;
}

IntDistribution make_int_distribution(const std::string& what, int64_t low, int64_t high, bool log,
                                      int64_t step) {
  if (low > high)
    fail(what, "low must be <= high (low=" + std::to_string(low) +
                   ", high=" + std::to_string(high) + ")");
  if (log && low < 1) fail(what, "a log distribution needs low >= 1");
  if (step <= 0) fail(what, "step must be >= 1");
  if (log && step != 1) fail(what, "`step` and `log` cannot be used together (as in Optuna)");
  IntDistribution d{low, high, log, step};
  d.high = (high - low) / step * step + low;  // Optuna's _adjust_int_uniform_high
  return d;
}

CategoricalDistribution make_categorical_distribution(const std::string& what,
                                                      std::vector<nlohmann::json> choices) {
  if (choices.empty()) fail(what, "a categorical parameter needs at least one choice");
  for (const auto& c : choices)
    if (!is_choice_type(c))
      fail(what,
           "a choice must be null, a bool, a number or a string (as Optuna's), not " + c.dump());
  return CategoricalDistribution{std::move(choices)};
}

std::string distribution_to_json(const Distribution& distribution) {
  // Key order as Optuna 3.1 writes them (json.dumps of _asdict()); Python does not care, a
  // reader of the file may.
  nlohmann::ordered_json out;
  if (const auto* f = std::get_if<FloatDistribution>(&distribution)) {
    out["name"] = "FloatDistribution";
    nlohmann::ordered_json a;
    a["step"] = f->step ? nlohmann::ordered_json(*f->step) : nlohmann::ordered_json(nullptr);
    a["low"] = f->low;
    a["high"] = f->high;
    a["log"] = f->log;
    out["attributes"] = a;
  } else if (const auto* i = std::get_if<IntDistribution>(&distribution)) {
    out["name"] = "IntDistribution";
    nlohmann::ordered_json a;
    a["log"] = i->log;
    a["step"] = i->step;
    a["low"] = i->low;
    a["high"] = i->high;
    out["attributes"] = a;
  } else {
    const auto& c = std::get<CategoricalDistribution>(distribution);
    out["name"] = "CategoricalDistribution";
    nlohmann::ordered_json choices = nlohmann::ordered_json::array();
    for (const auto& choice : c.choices)
      choices.push_back(nlohmann::ordered_json::parse(choice.dump()));
    out["attributes"] = {{"choices", choices}};
  }
  return out.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
}

namespace {

double number(const nlohmann::json& j, const char* key, const std::string& origin) {
  if (!j.contains(key) || !j[key].is_number())
    throw ConfigError(origin + ": distribution field '" + key + "' must be a number");
  return j[key].get<double>();
}

int64_t integer(const nlohmann::json& j, const char* key, const std::string& origin) {
  double v = number(j, key, origin);
  if (!(std::fabs(v) < 9e15) || v != std::floor(v))
    throw ConfigError(origin + ": distribution field '" + key + "' must be an integer");
  return static_cast<int64_t>(v);
}

bool flag(const nlohmann::json& j, const char* key, const std::string& origin) {
  if (!j.contains(key) || j[key].is_null()) return false;
  if (!j[key].is_boolean())
    throw ConfigError(origin + ": distribution field '" + std::string(key) +
                      "' must be true or false");
  return j[key].get<bool>();
}

}  // namespace

Distribution distribution_from_json(const std::string& text, const std::string& origin) {
  nlohmann::json j = nlohmann::json::parse(text, nullptr, /*allow_exceptions=*/false);
  if (!j.is_object()) throw ConfigError(origin + ": a distribution is not a JSON object");
  if (j.contains("name")) {
    if (!j["name"].is_string() || !j.contains("attributes") || !j["attributes"].is_object())
      throw ConfigError(origin + ": a distribution needs a name and attributes");
    const std::string name = j["name"];
    const auto& a = j["attributes"];
    if (name == "FloatDistribution") {
      std::optional<double> step;
      if (a.contains("step") && !a["step"].is_null()) step = number(a, "step", origin);
      return make_float_distribution(origin, number(a, "low", origin), number(a, "high", origin),
                                     flag(a, "log", origin), step);
    }
    if (name == "IntDistribution") {
      int64_t step = a.contains("step") ? integer(a, "step", origin) : 1;
      return make_int_distribution(origin, integer(a, "low", origin), integer(a, "high", origin),
                                   flag(a, "log", origin), step);
    }
    if (name == "CategoricalDistribution") {
      if (!a.contains("choices") || !a["choices"].is_array())
        throw ConfigError(origin + ": a categorical distribution needs a list of choices");
      return make_categorical_distribution(origin, a["choices"].get<std::vector<nlohmann::json>>());
    }
    throw ConfigError(
        origin + ": unknown distribution class '" + name +
        "' (rlrun reads FloatDistribution, IntDistribution, CategoricalDistribution)");
  }
  // The abbreviated form: {"type": "float"|"int"|"categorical", ...}.
  if (!j.contains("type") || !j["type"].is_string())
    throw ConfigError(origin + ": a distribution needs a name or a type");
  const std::string type = j["type"];
  if (type == "categorical") {
    if (!j.contains("choices") || !j["choices"].is_array())
      throw ConfigError(origin + ": a categorical distribution needs a list of choices");
    return make_categorical_distribution(origin, j["choices"].get<std::vector<nlohmann::json>>());
  }
  if (type == "float") {
    std::optional<double> step;
    if (j.contains("step") && !j["step"].is_null()) step = number(j, "step", origin);
    return make_float_distribution(origin, number(j, "low", origin), number(j, "high", origin),
                                   flag(j, "log", origin), step);
  }
  if (type == "int") {
    int64_t step = j.contains("step") && !j["step"].is_null() ? integer(j, "step", origin) : 1;
    return make_int_distribution(origin, integer(j, "low", origin), integer(j, "high", origin),
                                 flag(j, "log", origin), step);
  }
  throw ConfigError(origin + ": unknown distribution type '" + type + "'");
}

bool single(const Distribution& distribution) {
  if (const auto* f = std::get_if<FloatDistribution>(&distribution)) {
    if (f->low == f->high) return true;
    return f->step && (f->high - f->low) < *f->step;
  }
  if (const auto* i = std::get_if<IntDistribution>(&distribution)) {
    if (i->low == i->high) return true;
    return !i->log && (i->high - i->low) < i->step;
  }
  return std::get<CategoricalDistribution>(distribution).choices.size() == 1;
}

bool contains(const Distribution& distribution, double value) {
  if (std::isnan(value)) return false;
  if (const auto* f = std::get_if<FloatDistribution>(&distribution)) {
    if (!f->step) return f->low <= value && value <= f->high;
    double k = std::round((value - f->low) / *f->step);
    return f->low <= value && value <= f->high &&
           std::fabs(value - (f->low + k * *f->step)) <= 1e-8 * std::max(1.0, std::fabs(value));
  }
  if (const auto* i = std::get_if<IntDistribution>(&distribution)) {
    if (value != std::floor(value) || value < static_cast<double>(i->low) ||
        value > static_cast<double>(i->high))
      return false;
    return (static_cast<int64_t>(value) - i->low) % i->step == 0;
  }
  const auto& c = std::get<CategoricalDistribution>(distribution);
  return value >= 0 && value < static_cast<double>(c.choices.size()) && value == std::floor(value);
}

nlohmann::json to_external(const Distribution& distribution, double internal) {
  if (std::holds_alternative<FloatDistribution>(distribution)) return internal;
  if (std::holds_alternative<IntDistribution>(distribution)) return static_cast<int64_t>(internal);
  const auto& c = std::get<CategoricalDistribution>(distribution);
  auto index = static_cast<size_t>(internal);
  if (!(internal >= 0) || index >= c.choices.size())
    throw ConfigError("a categorical index out of range: " + std::to_string(internal));
  return c.choices[index];
}

double to_internal(const Distribution& distribution, const nlohmann::json& external) {
  if (const auto* c = std::get_if<CategoricalDistribution>(&distribution)) {
    for (size_t k = 0; k < c->choices.size(); ++k)
      if (same_choice(c->choices[k], external)) return static_cast<double>(k);
    throw ConfigError("'" + external.dump() + "' is not one of the choices");
  }
  double v = 0;
  if (external.is_number())
    v = external.get<double>();
  else if (external.is_boolean())
    v = external.get<bool>() ? 1 : 0;
  else
    throw ConfigError("'" + external.dump() + "' is not a number");
  if (std::isnan(v)) throw ConfigError("NaN is not a parameter value");
  return v;
}

bool compatible(const Distribution& a, const Distribution& b) {
  if (a.index() != b.index()) return false;
  if (const auto* ca = std::get_if<CategoricalDistribution>(&a))
    return ca->choices == std::get<CategoricalDistribution>(b).choices;
  return true;
}

}  // namespace rlrun::tune
