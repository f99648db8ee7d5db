#include "rlrun/core/config_node.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>

#include "rlrun/core/errors.hpp"

namespace rlrun {

namespace {

std::string position(const std::string& origin, const YAML::Mark& mark) {
  if (mark.is_null()) return origin;
  return origin + ":" + std::to_string(mark.line + 1) + ":" + std::to_string(mark.column + 1);
}

size_t edit_distance(const std::string& a, const std::string& b) {
  std::vector<size_t> prev(b.size() + 1), cur(b.size() + 1);
  for (size_t j = 0; j <= b.size(); ++j) prev[j] = j;
  for (size_t i = 1; i <= a.size(); ++i) {
    cur[0] = i;
    for (size_t j = 1; j <= b.size(); ++j) {
      const size_t substitute = prev[j - 1] + (std::tolower(a[i - 1]) != std::tolower(b[j - 1]));
      cur[j] = std::min({prev[j] + 1, cur[j - 1] + 1, substitute});
    }
    std::swap(prev, cur);
  }
  return prev[b.size()];
}

// YAML 1.1 allows 100_000; yaml-cpp does not, SB3 users write it. Strip the underscores.
std::string strip_digit_separators(std::string s) {
  if (s.find('_') == std::string::npos) return s;
  std::string out;
  for (size_t i = 0; i < s.size(); ++i) {
    const bool between_digits = i > 0 && i + 1 < s.size() && std::isdigit(s[i - 1]) &&
                                std::isdigit(s[i + 1]);
    if (s[i] == '_' && between_digits) continue;
    out += s[i];
  }
  return out;
}

}  // namespace

std::string closest_name(const std::string& name, const std::vector<std::string>& candidates) {
  std::string best;
  size_t best_distance = std::string::npos;
  for (const auto& candidate : candidates) {
    const size_t d = edit_distance(name, candidate);
    if (d < best_distance) {
      best_distance = d;
      best = candidate;
    }
  }
  // Plausible typo: a few edits relative to the length, or one is a prefix of the other.
  const size_t limit = std::max<size_t>(2, name.size() / 3);
  if (best_distance <= limit) return best;
  for (const auto& candidate : candidates)
    if (!name.empty() && (candidate.rfind(name, 0) == 0 || name.rfind(candidate, 0) == 0))
      return candidate;
  return "";
}

std::string did_you_mean(const std::string& name, const std::vector<std::string>& candidates) {
  const std::string best = closest_name(name, candidates);
  return best.empty() ? "" : " (did you mean '" + best + "'?)";
}

ConfigNode ConfigNode::load_file(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw ConfigError(path + ": cannot open config file");
  std::stringstream text;
  text << in.rdbuf();
  return load_string(text.str(), path);
}

ConfigNode ConfigNode::load_string(const std::string& text, const std::string& origin) {
  auto context = std::make_shared<Context>();
  context->origin = origin;
  try {
    YAML::Node node = YAML::Load(text);
    if (!node.IsDefined() || node.IsNull()) node = YAML::Node(YAML::NodeType::Map);
    return ConfigNode(node, context, "");
  } catch (const YAML::ParserException& e) {
    throw ConfigError(position(origin, e.mark) + ": invalid YAML: " + e.msg);
  }
}

ConfigNode ConfigNode::from_yaml(YAML::Node node, const std::string& origin, std::string path) {
  auto context = std::make_shared<Context>();
  context->origin = origin;
  return ConfigNode(std::move(node), context, std::move(path));
}

void ConfigNode::apply_override(const std::string& assignment) {
  const auto eq = assignment.find('=');
  if (eq == std::string::npos || eq == 0)
    throw UsageError("--set " + assignment + ": expected key.path=value");
  const std::string key_path = assignment.substr(0, eq);
  const std::string value_text = assignment.substr(eq + 1);
  YAML::Node value;
  try {
    value = YAML::Load(value_text);
  } catch (const YAML::ParserException& e) {
    throw UsageError("--set " + assignment + ": value is not valid YAML: " + e.msg);
  }
  std::vector<std::string> parts;
  std::stringstream ss(key_path);
  for (std::string part; std::getline(ss, part, '.');) {
    if (part.empty()) throw UsageError("--set " + assignment + ": empty key in path");
    parts.push_back(part);
  }
  // Walk with YAML::Node copies (they are handles): create maps on the way.
  std::vector<YAML::Node> chain{node_};
  for (size_t i = 0; i + 1 < parts.size(); ++i) {
    YAML::Node next = chain.back()[parts[i]];
    if (!next.IsDefined() || next.IsNull()) {
      chain.back()[parts[i]] = YAML::Node(YAML::NodeType::Map);
      next = chain.back()[parts[i]];
    } else if (!next.IsMap()) {
      throw UsageError("--set " + assignment + ": '" + parts[i] + "' is not a map");
    }
    chain.push_back(next);
  }
  chain.back()[parts.back()] = value;
  context_->override_paths.push_back(key_path);
  context_->override_texts.push_back(assignment);
}

bool ConfigNode::has(const std::string& key) const {
  if (!is_map()) return false;
  const YAML::Node& self = node_;
  return self[key].IsDefined();
}

ConfigNode ConfigNode::child(const std::string& key) const {
  const std::string child_path = path_.empty() ? key : path_ + "." + key;
  if (!is_map()) return ConfigNode(YAML::Node(YAML::NodeType::Undefined), context_, child_path);
  const YAML::Node& self = node_;
  return ConfigNode(self[key], context_, child_path);
}

ConfigNode ConfigNode::at(std::size_t index) const {
  const YAML::Node& self = node_;
  return ConfigNode(self[index], context_, path_ + "[" + std::to_string(index) + "]");
}

std::vector<std::string> ConfigNode::keys() const {
  std::vector<std::string> out;
  if (!is_map()) return out;
  // YAML allows a list or map as a key ({[a]: 1}); as<std::string>() would throw yaml-cpp's
  // BadConversion past every handler (found by fuzz/fuzz_config.cpp).
  for (const auto& kv : node_) {
    if (!kv.first.IsScalar() && !kv.first.IsNull()) fail("a key must be a name, not a list or map");
    out.push_back(kv.first.Scalar());
  }
  return out;
}

std::string ConfigNode::where() const {
  for (size_t i = context_->override_paths.size(); i-- > 0;) {
    const std::string& p = context_->override_paths[i];
    if (path_ == p || path_.rfind(p + ".", 0) == 0 || path_.rfind(p + "[", 0) == 0)
      return "--set " + context_->override_texts[i];
  }
  if (node_.IsDefined()) return position(context_->origin, node_.Mark());
  return context_->origin;
}

void ConfigNode::fail(const std::string& message) const {
  throw ConfigError(where() + ": " + (path_.empty() ? "" : path_ + ": ") + message);
}

void ConfigNode::fail_at_key(const std::string& key, const std::string& message) const {
  const ConfigNode value = child(key);
  std::string where = value.where();
  if (where.rfind("--set", 0) != 0 && is_map()) {
    for (const auto& kv : node_)
      if (kv.first.IsScalar() && kv.first.Scalar() == key) where = position(context_->origin, kv.first.Mark());
  }
  throw ConfigError(where + ": " + value.path() + ": " + message);
}

std::string ConfigNode::as_string() const {
  if (!is_scalar()) fail("expected a string");
  return node_.Scalar();
}

double ConfigNode::as_double() const {
  if (!is_scalar()) fail("expected a number");
  const std::string text = strip_digit_separators(node_.Scalar());
  try {
    size_t used = 0;
    const double v = std::stod(text, &used);
    if (used == text.size()) return v;
  } catch (const std::exception&) {
  }
  fail("expected a number, got '" + node_.Scalar() + "'");
}

int64_t ConfigNode::as_int() const {
  if (!is_scalar()) fail("expected an integer");
  // Accept 1e5 and 100_000: rl-zoo files write timesteps that way.
  const std::string text = strip_digit_separators(node_.Scalar());
  try {
    size_t used = 0;
    const double v = std::stod(text, &used);
    if (used == text.size() && std::floor(v) == v && std::abs(v) < 9.0e15)
      return static_cast<int64_t>(v);
  } catch (const std::exception&) {
  }
  fail("expected an integer, got '" + node_.Scalar() + "'");
}

bool ConfigNode::as_bool() const {
  if (is_scalar()) {
    std::string s = node_.Scalar();
    std::transform(s.begin(), s.end(), s.begin(), ::tolower);
    if (s == "true" || s == "yes" || s == "on") return true;
    if (s == "false" || s == "no" || s == "off") return false;
  }
  fail("expected true or false, got '" + (is_scalar() ? node_.Scalar() : "a non-scalar") +
       "'");
}

}  // namespace rlrun
