#pragma once
// Reading and writing `Config` structs. Each component's Config owns its defaults and lists its
// fields once, in a member template
//     template <class V> void visit(V& v) { v("n_steps", n_steps, "rollout length per env"); }
// The same list drives strict parsing (unknown keys are errors with a did-you-mean), writing
// the fully resolved config, and `rlrun list --params` documentation.
#include <yaml-cpp/yaml.h>

#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>
#include <algorithm>
#include <sstream>
#include <string>
#include <type_traits>
#include <vector>

#include "rlrun/core/config_node.hpp"
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
    n.fail("integer out of range (at most " + std::to_string(std::numeric_limits<int>::max()) + ")");
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

// --- visitors -------------------------------------------------------------------------------

// Strict reader: fills fields present in the node, keeps defaults for the rest, and finish()
// rejects any key that no field claimed.
class ConfigReader {
 public:
  // `reserved` keys belong to the enclosing section (e.g. `id`) and are not errors.
  explicit ConfigReader(const ConfigNode& node, std::vector<std::string> reserved = {})
      : node_(node), reserved_(std::move(reserved)) {
    if (node_.defined() && !node_.is_map()) node_.fail("expected a map of key: value");
  }

  template <class T>
  void operator()(const char* key, T& field, const char* /*doc*/) {
    known_.push_back(key);
    if (!node_.has(key)) return;
    const ConfigNode child = node_.child(key);
    if (!child.defined()) {
      if constexpr (requires { field.reset(); }) field.reset();
      return;
    }
    decode(child, field);
  }

  void finish() const {
    if (!node_.defined()) return;
    std::vector<std::string> valid = known_;
    valid.insert(valid.end(), reserved_.begin(), reserved_.end());
    for (const auto& key : node_.keys()) {
      if (std::find(valid.begin(), valid.end(), key) != valid.end()) continue;
      node_.fail_at_key(key, "unknown key '" + key + "'" + did_you_mean(key, known_) +
                                 "; valid keys: " + join(known_));
    }
  }

 private:
  static std::string join(const std::vector<std::string>& v) {
    std::string s;
    for (const auto& x : v) s += (s.empty() ? "" : ", ") + x;
    return s;
  }
  ConfigNode node_;
  std::vector<std::string> reserved_;
  std::vector<std::string> known_;
};

// Writes every field (defaults included) as a YAML map: the resolved config.
class ConfigWriter {
 public:
  template <class T>
  void operator()(const char* key, T& field, const char* /*doc*/) {
    node_[key] = encode(field);
  }
  YAML::Node node() const { return node_; }

 private:
  YAML::Node node_{YAML::NodeType::Map};
};

// Collects (key, default, doc) rows for `rlrun list --params`.
struct FieldDoc {
  std::string key, default_value, doc;
};
class ConfigDocumenter {
 public:
  template <class T>
  void operator()(const char* key, T& field, const char* doc) {
    YAML::Emitter out;
    out.SetMapFormat(YAML::Flow);
    out.SetSeqFormat(YAML::Flow);
    out << encode(field);
    rows_.push_back({key, out.c_str(), doc});
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
