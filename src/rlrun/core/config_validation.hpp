#pragma once
// Validation once (issue 42): a Config's visit() is the one list of its fields and their
// constraints. read_config (config_fields.hpp) checks them while a file is read, with the
// file:line:col of each bad value; a component's constructor, which may also get a Config built
// in code (tests, benchmarks, the tuner), checks the same list with valid_config and adds only
// the rules that need more than one value or the env's spaces.
#include <optional>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

#include "rlrun/core/config_checks.hpp"
#include "rlrun/core/schedule.hpp"

namespace rlrun {

// "" or why `value` breaks `check`: the rules of check_value in config_fields.hpp, without a
// node to point at. A field whose type has no overload here (a net_arch, checked where its
// networks are built) is left to its component.
template <class T>
requires std::is_arithmetic_v<T> std::string value_problem(const T& value, const Bounds& bounds) {
  return bounds.problem(static_cast<double>(value));
}
// A linear schedule starts at its initial value and ends at 0 (rl-zoo's linear_schedule).
inline std::string value_problem(const Schedule& value, const Bounds& bounds) {
  return bounds.problem(value.initial());
}
inline std::string value_problem(const std::string& value, const OneOf& allowed) {
  for (const std::string& name : allowed.names)
    if (name == value) return "";
  return "unknown value '" + value + "'; " + allowed.describe();
}
template <class C>
requires requires(const C& c, const std::string& s) { c.problem(s); }
std::string value_problem(const std::string& value, const C& check) { return check.problem(value); }
template <class T, class C>
requires requires(const T& t, const C& c) { value_problem(t, c); }
std::string value_problem(const std::optional<T>& value, const C& check) {
  return value ? value_problem(*value, check) : "";
}
template <class T, class C>
requires requires(const T& t, const C& c) { value_problem(t, c); }
std::string value_problem(const std::vector<T>& values, const C& check) {
  for (std::size_t i = 0; i < values.size(); ++i)
    if (std::string p = value_problem(values[i], check); !p.empty())
      return "[" + std::to_string(i) + "] " + p;
  return "";
}

// Collects "key must be ..., got ..." for every field that breaks its constraint; nested
// sections (a struct with its own visit, such as policy) as "policy.key".
class ConfigValidator {
 public:
  explicit ConfigValidator(std::string prefix = "") : prefix_(std::move(prefix)) {}

  template <class T>
  void operator()(const char* key, T& field, const char* /*doc*/) {
    if constexpr (requires(ConfigValidator & nested) { field.visit(nested); }) {
      ConfigValidator nested(prefix_ + key + ".");
      field.visit(nested);
      problems_.insert(problems_.end(), nested.problems_.begin(), nested.problems_.end());
    }
  }
  template <class T, class C>
  void operator()(const char* key, T& field, const char* doc, const C& check) {
    (*this)(key, field, doc);
    if constexpr (requires { value_problem(field, check); }) {
      if (std::string p = value_problem(field, check); !p.empty())
        problems_.push_back(prefix_ + key + " " + p);
    }
  }
  const std::vector<std::string>& problems() const { return problems_; }

 private:
  std::string prefix_;
  std::vector<std::string> problems_;
};

// `config` itself when every field meets its visit() constraint; otherwise throws
// std::invalid_argument "<owner>: <key> must be ..., got ..." (all problems, "; " between).
template <class C>
const C& valid_config(const C& config, const std::string& owner) {
  C copy = config;  // visit() hands out mutable references
  ConfigValidator validator;
  copy.visit(validator);
  if (validator.problems().empty()) return config;
  std::string message = owner + ": ";
  for (std::size_t i = 0; i < validator.problems().size(); ++i)
    message += (i ? "; " : "") + validator.problems()[i];
  throw std::invalid_argument(message);
}

}  // namespace rlrun
