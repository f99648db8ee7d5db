#pragma once
// Reading and writing `Config` structs. Each component's Config owns its defaults and lists its
// fields once, in a member template
//     template <class V> void visit(V& v) { v("n_steps", n_steps, "rollout length per env"); }
// The same list drives strict parsing (unknown keys are errors with a did-you-mean), writing
// the fully resolved config, and `rlrun list --params` documentation. A field may carry a
// constraint (core/config_checks.hpp) as a fourth argument:
//     v("gamma", gamma, "discount factor", unit_interval());
// The reader reports every problem of a section at once (each with file:line:col), not only the
// first.
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>
#include <sstream>
#include <string>
#include <type_traits>
#include <vector>

#include "rlrun/core/config_checks.hpp"
#include "rlrun/core/config_node.hpp"
#include "rlrun/core/errors.hpp"
#include "rlrun/core/float_format.hpp"
#include "rlrun/core/schedule.hpp"

namespace rlrun {

// --- decoding one value -------------------------------------------------------------------
inline void decode(const ConfigNode& n, std::string& out) { out = n.as_string(); }
inline void decode(const ConfigNode& n, double& out) { out = n.as_double(); }
inline void decode(const ConfigNode& n, float& out) {
  const double v = n.as_double();
  // A finite double beyond float's range has no float value (converting it is undefined).
  if (std::isfinite(v) && std::fabs(v) > std::numeric_limits<float>::max())
    n.fail("number out of range (a float32 setting)");
  out = static_cast<float>(v);
}
inline void decode(const ConfigNode& n, bool& out) { out = n.as_bool(); }
inline void decode(const ConfigNode& n, int& out) {
  const int64_t v = n.as_int();
  if (v < std::numeric_limits<int>::min() || v > std::numeric_limits<int>::max())
    n.fail("expected an integer in [" + std::to_string(std::numeric_limits<int>::min()) + ", " +
           std::to_string(std::numeric_limits<int>::max()) + "], got " + std::to_string(v));
  out = static_cast<int>(v);
}
inline void decode(const ConfigNode& n, int64_t& out) { out = n.as_int(); }
inline void decode(const ConfigNode& n, uint64_t& out) {
  const int64_t v = n.as_int();
  if (v < 0) n.fail("expected a non-negative integer");
  out = static_cast<uint64_t>(v);
}
inline void decode(const ConfigNode& n, Schedule& out) {
  try {
    out = Schedule::parse(n.as_string());
  } catch (const std::invalid_argument& e) {
    n.fail(e.what());
  }
}
template <class T>
void decode(const ConfigNode& n, std::vector<T>& out) {
  if (!n.is_sequence()) n.fail("expected a list, e.g. [64, 64]");
  out.clear();
  for (std::size_t i = 0; i < n.size(); ++i) {
    T item{};
    decode(n.at(i), item);
    out.push_back(std::move(item));
  }
}
template <class T>
void decode(const ConfigNode& n, std::optional<T>& out) {
  if (!n.defined()) {
    out.reset();
    return;
  }
  T value{};
  decode(n, value);
  out = std::move(value);
}

class ConfigReader;
template <class T>
requires requires(T t, ConfigReader& r) { t.visit(r); }
void decode(const ConfigNode& n, T& out);

// --- encoding one value -------------------------------------------------------------------
inline YAML::Node encode(const std::string& v) { return YAML::Node(v); }
// Numbers are written as Python writes them (0.98, not 0.97999999999999998).
inline YAML::Node encode(double v) { return YAML::Node(python_float_repr(v)); }
inline YAML::Node encode(float v) { return YAML::Node(python_float_repr(static_cast<double>(v))); }
inline YAML::Node encode(bool v) { return YAML::Node(v); }
inline YAML::Node encode(int v) { return YAML::Node(v); }
inline YAML::Node encode(int64_t v) { return YAML::Node(v); }
inline YAML::Node encode(uint64_t v) { return YAML::Node(v); }
inline YAML::Node encode(const Schedule& v) {
  return YAML::Node(v.is_linear() ? v.str() : python_float_repr(v.initial()));
}
template <class T>
YAML::Node encode(const std::vector<T>& v) {
  YAML::Node seq(YAML::NodeType::Sequence);
  for (const auto& item : v) seq.push_back(encode(item));
  seq.SetStyle(YAML::EmitterStyle::Flow);
  return seq;
}
template <class T>
YAML::Node encode(const std::optional<T>& v) {
  return v ? encode(*v) : YAML::Node(YAML::NodeType::Null);
}
class ConfigWriter;
template <class T>
requires requires(T t, ConfigWriter& w) { t.visit(w); }
YAML::Node encode(const T& v);

// --- checking one value against its constraint ---------------------------------------------
inline std::string describe_check(const Bounds& b) { return b.describe(); }
inline std::string describe_check(const OneOf& o) { return o.describe(); }
template <class C>
requires requires(const C& c, const std::string& s) { c.problem(s); }
std::string describe_check(const C& c) { return c.describe(); }

template <class T>
requires std::is_arithmetic_v<T>
void check_value(const ConfigNode& n, const T& value, const Bounds& bounds) {
  const std::string problem = bounds.problem(static_cast<double>(value));
  if (!problem.empty()) n.fail(problem);
}
inline void check_value(const ConfigNode& n, const Schedule& value, const Bounds& bounds) {
  // A linear schedule starts at its initial value and ends at 0 (rl-zoo's linear_schedule).
  const std::string problem = bounds.problem(value.initial());
  if (!problem.empty()) n.fail(problem);
}
inline void check_value(const ConfigNode& n, const std::string& value, const OneOf& allowed) {
  if (std::find(allowed.names.begin(), allowed.names.end(), value) != allowed.names.end()) return;
  n.fail("unknown value '" + value + "'" + did_you_mean(value, allowed.names) + "; " +
         allowed.describe());
}
template <class C>
requires requires(const C& c, const std::string& s) { c.problem(s); }
void check_value(const ConfigNode& n, const std::string& value, const C& check) {
  const std::string problem = check.problem(value);
  if (!problem.empty()) n.fail(problem);
}
template <class T, class C>
void check_value(const ConfigNode& n, const std::optional<T>& value, const C& check) {
  if (value) check_value(n, *value, check);
}
template <class T, class C>
void check_value(const ConfigNode& n, const std::vector<T>& values, const C& check) {
  for (std::size_t i = 0; i < values.size(); ++i) check_value(n.at(i), values[i], check);
}

// --- visitors -------------------------------------------------------------------------------

// Strict reader: fills fields present in the node, keeps defaults for the rest, and finish()
// rejects any key that no field claimed. Problems are collected, so one run shows all of a
// section's errors; finish() throws them together as one ConfigError (one line each).
class ConfigReader {
 public:
  // `reserved` keys belong to the enclosing section (e.g. `id`) and are not errors.
  explicit ConfigReader(const ConfigNode& node, std::vector<std::string> reserved = {})
      : node_(node), reserved_(std::move(reserved)) {
    if (node_.defined() && !node_.is_map()) node_.fail("expected a map of key: value");
  }

  template <class T>
  void operator()(const char* key, T& field, const char* /*doc*/) {
    read(key, field, [](const ConfigNode&, const T&) {});
  }
  template <class T, class C>
  void operator()(const char* key, T& field, const char* /*doc*/, const C& check) {
    read(key, field,
         [&check](const ConfigNode& n, const T& value) { check_value(n, value, check); });
  }

  // Unknown keys join the problems found so far; throws them all, if any.
  void finish() {
    if (node_.defined()) {
      std::vector<std::string> valid = known_;
      valid.insert(valid.end(), reserved_.begin(), reserved_.end());
      for (const auto& key : node_.keys()) {
        if (std::find(valid.begin(), valid.end(), key) != valid.end()) continue;
        try {
          node_.fail_at_key(key, "unknown key '" + key + "'" + did_you_mean(key, valid) +
                                     "; valid keys: " + join(valid));
        } catch (const ConfigError& e) {
          problems_.push_back(e.what());
        }
      }
    }
    if (problems_.empty()) return;
    std::string message;
    for (const auto& p : problems_) message += (message.empty() ? "" : "\n") + p;
    problems_.clear();
    throw ConfigError(message);
  }

 private:
  template <class T, class Check>
  void read(const char* key, T& field, const Check& check) {
    known_.push_back(key);
    if (!node_.has(key)) return;
    const ConfigNode child = node_.child(key);
    try {
      if (!child.defined()) {
        if constexpr (requires { field.reset(); }) field.reset();
        return;
      }
      decode(child, field);
      check(child, field);
    } catch (const ConfigError& e) {
      problems_.push_back(e.what());
    }
  }
  static std::string join(const std::vector<std::string>& v) {
    std::string s;
    for (const auto& x : v) s += (s.empty() ? "" : ", ") + x;
    return s;
  }
  ConfigNode node_;
  std::vector<std::string> reserved_;
  std::vector<std::string> known_;
  std::vector<std::string> problems_;
};

// Writes every field (defaults included) as a YAML map: the resolved config.
class ConfigWriter {
 public:
  template <class T>
  void operator()(const char* key, T& field, const char* /*doc*/) {
    node_[key] = encode(field);
  }
  template <class T, class C>
  void operator()(const char* key, T& field, const char* doc, const C& /*check*/) {
    (*this)(key, field, doc);
  }
  YAML::Node node() const { return node_; }

 private:
  YAML::Node node_{YAML::NodeType::Map};
};

// Collects (key, default, doc) rows for `rlrun list --params`.
struct FieldDoc {
  std::string key, default_value, doc;
  std::string constraint;  // e.g. "in [0, 1]"; empty: none
};
// A nested section (a struct with its own visit, such as algo.policy) gives one row per field,
// keyed "policy.net_arch", so its defaults and docs read like the others'.
class ConfigDocumenter {
 public:
  template <class T>
  void operator()(const char* key, T& field, const char* doc) {
    if constexpr (requires(ConfigDocumenter & d) { field.visit(d); }) {
      ConfigDocumenter nested;
      field.visit(nested);
      for (FieldDoc row : nested.rows()) {
        row.key = std::string(key) + "." + row.key;
        rows_.push_back(std::move(row));
      }
      (void)doc;
      return;
    }
    YAML::Emitter out;
    out.SetMapFormat(YAML::Flow);
    out.SetSeqFormat(YAML::Flow);
    out << encode(field);
    rows_.push_back({key, out.c_str(), doc, ""});
  }
  template <class T, class C>
  void operator()(const char* key, T& field, const char* doc, const C& check) {
    const size_t before = rows_.size();
    (*this)(key, field, doc);
    if (rows_.size() == before + 1) rows_.back().constraint = describe_check(check);
  }
  const std::vector<FieldDoc>& rows() const { return rows_; }

 private:
  std::vector<FieldDoc> rows_;
};

template <class T>
requires requires(T t, ConfigReader& r) { t.visit(r); }
void decode(const ConfigNode& n, T& out) {
  ConfigReader reader(n);
  out.visit(reader);
  reader.finish();
}

template <class T>
requires requires(T t, ConfigWriter& w) { t.visit(w); }
YAML::Node encode(const T& v) {
  T copy = v;
  ConfigWriter writer;
  copy.visit(writer);
  return writer.node();
}

// Parses a whole Config from a node (absent node => all defaults).
template <class C>
C read_config(const ConfigNode& node, std::vector<std::string> reserved = {}) {
  C config{};
  ConfigReader reader(node, std::move(reserved));
  config.visit(reader);
  reader.finish();
  return config;
}

template <class C>
YAML::Node write_config(const C& config) {
  return encode(config);
}

template <class C>
std::vector<FieldDoc> document_config() {
  C config{};
  ConfigDocumenter documenter;
  config.visit(documenter);
  return documenter.rows();
}

}  // namespace rlrun
