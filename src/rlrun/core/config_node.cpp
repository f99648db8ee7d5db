#include "rlrun/core/config_node.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>
#include <unordered_set>

#include <yaml-cpp/eventhandler.h>

#include "rlrun/core/errors.hpp"
#include "rlrun/core/quoted_text.hpp"

namespace rlrun {

namespace {

std::string position(const std::string& origin, const YAML::Mark& mark) {
  if (mark.is_null()) return origin;
  return origin + ":" + std::to_string(mark.line + 1) + ":" + std::to_string(mark.column + 1);
}

// Where each YAML document of a text starts, read from the parser's events (no nodes are
// built, no alias is expanded).
class DocumentStarts : public YAML::EventHandler {
 public:
  std::vector<YAML::Mark> starts;
  void OnDocumentStart(const YAML::Mark& mark) override { starts.push_back(mark); }
  void OnDocumentEnd() override {}
  void OnNull(const YAML::Mark&, YAML::anchor_t) override {}
  void OnAlias(const YAML::Mark&, YAML::anchor_t) override {}
  void OnScalar(const YAML::Mark&, const std::string&, YAML::anchor_t,
                const std::string&) override {}
  void OnSequenceStart(const YAML::Mark&, const std::string&, YAML::anchor_t,
                       YAML::EmitterStyle::value) override {}
  void OnSequenceEnd() override {}
  void OnMapStart(const YAML::Mark&, const std::string&, YAML::anchor_t,
                  YAML::EmitterStyle::value) override {}
  void OnMapEnd() override {}
};

// A config text holds one YAML document. yaml-cpp (0.7) does not report a ',' ']' or '}' at the
// start of a document: it yields an empty document there without moving on, forever
// (YAML::LoadAll never returns). So at most two documents are read, and a second one that
// starts where the first did is that stray character.
void check_one_document(const std::string& text, const std::string& origin) {
  std::istringstream in(text);
  YAML::Parser parser(in);
  DocumentStarts documents;
  while (documents.starts.size() < 2 && parser.HandleNextDocument(documents)) {
  }
  if (documents.starts.size() < 2) return;
  const YAML::Mark& first = documents.starts[0];
  const YAML::Mark& second = documents.starts[1];
  if (second.pos == first.pos)
    throw ConfigError(position(origin, second) +
                      ": invalid YAML: a ',', ']' or '}' outside any [list] or {map}");
  throw ConfigError(position(origin, second) +
                    ": a second YAML document ('---'): a config file holds one");
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
    const bool between_digits =
        i > 0 && i + 1 < s.size() && std::isdigit(s[i - 1]) && std::isdigit(s[i + 1]);
    if (s[i] == '_' && between_digits) continue;
    out += s[i];
  }
  return out;
}

// Counts nodes with aliases expanded (a "billion laughs" file is refused before anything walks
// it), refuses a collection that holds itself through an alias (`a: &x {b: *x}`, or a map that
// merges itself with `<<: *x`: endless, and found at once rather than after the count's bound
// of expansions), and refuses a key written twice in one map, naming both places.
void check_structure(const YAML::Node& root, const std::string& origin) {
  std::size_t visited = 0;
  std::vector<std::string> duplicates;
  // Depth-first, with the collections from the root to the node being looked at: an alias
  // shares its anchor's node, so a collection that contains itself meets its own start
  // position (YAML::Mark::pos; distinct collections of one text start at distinct places).
  struct Visit {
    YAML::Node node;
    std::size_t depth;  // collections above it
  };
  std::vector<Visit> stack{{root, 0}};
  std::vector<int> path;
  std::unordered_set<int> on_path;
  while (!stack.empty()) {
    const Visit visit = stack.back();
    stack.pop_back();
    while (path.size() > visit.depth) {
      on_path.erase(path.back());
      path.pop_back();
    }
    const YAML::Node& node = visit.node;
    if (++visited > kMaxConfigNodes)
      throw ConfigError(origin + ": more than " + std::to_string(kMaxConfigNodes) +
                        " YAML values (with aliases expanded); an experiment file has a few "
                        "hundred");
    if (!node.IsSequence() && !node.IsMap()) continue;
    const int start = node.Mark().pos;
    if (start >= 0 && !on_path.insert(start).second)
      throw ConfigError(position(origin, node.Mark()) +
                        ": this value contains itself through an alias (a recursive alias, "
                        "endless when expanded)");
    path.push_back(start);
    const std::size_t depth = path.size();
    if (node.IsSequence()) {
      for (const auto& item : node) stack.push_back({item, depth});
    } else {
      std::vector<std::pair<std::string, YAML::Mark>> seen;
      for (const auto& kv : node) {
        const std::string key = kv.first.IsScalar() ? kv.first.Scalar() : std::string();
        if (!kv.first.IsScalar())
          throw ConfigError(position(origin, kv.first.Mark()) + ": a key must be a plain name");
        for (const auto& [other, mark] : seen)
          if (other == key)
            duplicates.push_back(position(origin, kv.first.Mark()) + ": key '" + key +
                                 "' repeats the one at line " + std::to_string(mark.line + 1) +
                                 ", column " + std::to_string(mark.column + 1) +
                                 " of the same map: write it once");
        seen.emplace_back(key, kv.first.Mark());
        stack.push_back({kv.second, depth});
      }
    }
  }
  if (duplicates.empty()) return;
  std::string message;
  for (const auto& d : duplicates) message += (message.empty() ? "" : "\n") + d;
  throw ConfigError(message);
}

// A merge key: `<<` written plain (or tagged !!merge); a quoted "<<" is an ordinary key.
bool is_merge_key(const YAML::Node& key) {
  return key.IsScalar() && key.Scalar() == "<<" &&
         (key.Tag() == "?" || key.Tag() == "tag:yaml.org,2002:merge");
}

// Merged maps that merge others, and so on: a chain this long is not a config.
constexpr int kMaxMergeDepth = 64;

// Resolves the merge key of `map`, if it has one (yaml.org/type/merge.html, as PyYAML's
// flatten_mapping): the keys of the merged map (or maps, earlier ones first) that `map` does not
// write itself are added to it, as the same nodes (their positions are the anchor's). yaml-cpp
// 0.7 reads `<<` as an ordinary key. The merged maps are resolved first; in document order
// (resolve_merge_keys) they already are, so the recursion stays shallow.
void merge_into(YAML::Node map, const std::string& origin, int depth) {
  YAML::Node merge_key, sources;
  bool found = false;
  for (const auto& kv : map) {
    if (!is_merge_key(kv.first)) continue;
    merge_key = kv.first;
    sources = kv.second;
    found = true;
  }
  if (!found) return;
  if (depth > kMaxMergeDepth)
    throw ConfigError(position(origin, merge_key.Mark()) + ": merge keys (<<) chained more than " +
                      std::to_string(kMaxMergeDepth) + " maps deep");
  std::vector<YAML::Node> merged;
  if (sources.IsMap()) merged.push_back(sources);
  if (sources.IsSequence())
    for (const YAML::Node& item : sources) merged.push_back(item);
  if (merged.empty() ||
      std::any_of(merged.begin(), merged.end(), [](const YAML::Node& m) { return !m.IsMap(); }))
    throw ConfigError(position(origin, merge_key.Mark()) +
                      ": a merge key (<<) takes a map or a list of maps, e.g. <<: *defaults or "
                      "<<: [*a, *b]");
  std::unordered_set<std::string> present;
  for (const auto& kv : map)
    if (!is_merge_key(kv.first)) present.insert(kv.first.Scalar());
  map.remove(merge_key);
  for (const YAML::Node& source : merged) {
    merge_into(source, origin, depth + 1);
    for (const auto& kv : source)
      if (present.insert(kv.first.Scalar()).second) map.force_insert(kv.first, kv.second);
  }
}

// Resolves every merge key of the tree, visiting maps in document order (an anchor comes before
// its aliases, so a merged map is resolved before the maps that merge it). check_structure has
// bounded the tree with aliases expanded, which bounds this walk; merging adds no node to it.
void resolve_merge_keys(const YAML::Node& root, const std::string& origin) {
  std::vector<YAML::Node> stack{root};
  while (!stack.empty()) {
    YAML::Node node = stack.back();
    stack.pop_back();
    std::vector<YAML::Node> children;
    if (node.IsMap()) {
      merge_into(node, origin, 0);
      for (const auto& kv : node) children.push_back(kv.second);
    } else if (node.IsSequence()) {
      for (const YAML::Node& item : node) children.push_back(item);
    }
    stack.insert(stack.end(), children.rbegin(), children.rend());
  }
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

ConfigNode ConfigNode::load_file(const std::string& path, ConfigTrust trust) {
  // Only regular files: a FIFO or a device named as a config would block or never end.
  std::error_code ec;
  if (std::filesystem::exists(path, ec) && !std::filesystem::is_regular_file(path, ec))
    throw ConfigError(path + ": not a regular file");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw ConfigError(path + ": cannot open config file");
  // Read at most one byte more than the bound: a huge file is refused without reading it all.
  std::string text(kMaxConfigBytes + 1, '\0');
  in.read(text.data(), static_cast<std::streamsize>(text.size()));
  text.resize(static_cast<std::size_t>(in.gcount()));
  return load_string(text, path, trust);
}

ConfigNode ConfigNode::load_string(const std::string& text, const std::string& origin,
                                   ConfigTrust trust) {
  if (text.size() > kMaxConfigBytes)
    throw ConfigError(origin + ": larger than " + std::to_string(kMaxConfigBytes >> 20) +
                      " MiB; an experiment file is a few kilobytes (is this the right file?)");
  if (text.find('\0') != std::string::npos)
    throw ConfigError(origin + ": contains a NUL byte; a config file is text");
  auto context = std::make_shared<Context>();
  context->origin = origin;
  context->trust = trust;
  YAML::Node node;
  try {
    check_one_document(text, origin);
    node = YAML::Load(text);
  } catch (const YAML::Exception& e) {
    throw ConfigError(position(origin, e.mark) + ": invalid YAML: " + e.msg);
  }
  if (!node.IsDefined() || node.IsNull()) node = YAML::Node(YAML::NodeType::Map);
  check_structure(node, origin);
  resolve_merge_keys(node, origin);
  return ConfigNode(node, context, "");
}

ConfigNode ConfigNode::from_yaml(YAML::Node node, const std::string& origin, std::string path,
                                 ConfigTrust trust) {
  auto context = std::make_shared<Context>();
  context->origin = origin;
  context->trust = trust;
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
    check_one_document(value_text, "--set " + assignment);
    value = YAML::Load(value_text);
    check_structure(value, "--set " + assignment);
    resolve_merge_keys(value, "--set " + assignment);
  } catch (const YAML::Exception& e) {
    throw UsageError("--set " + assignment + ": value is not valid YAML: " + e.msg);
  } catch (const ConfigError& e) {
    throw UsageError(e.what());
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
  context_->override_shown.push_back("--set " + assignment);
}

void ConfigNode::vouch_for(const std::string& key_path, const std::string& shown) {
  context_->override_paths.push_back(key_path);
  context_->override_shown.push_back(shown);
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

ConfigNode ConfigNode::without(const std::string& key) const {
  YAML::Node copy = YAML::Clone(node_);
  if (copy.IsMap()) copy.remove(key);
  return ConfigNode(copy, context_, path_);
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

bool ConfigNode::from_command_line() const {
  for (const std::string& p : context_->override_paths)
    if (path_ == p || path_.rfind(p + ".", 0) == 0 || path_.rfind(p + "[", 0) == 0) return true;
  return false;
}

std::string ConfigNode::where() const {
  for (size_t i = context_->override_paths.size(); i-- > 0;) {
    const std::string& p = context_->override_paths[i];
    if (path_ == p || path_.rfind(p + ".", 0) == 0 || path_.rfind(p + "[", 0) == 0)
      return context_->override_shown[i];
  }
  if (node_.IsDefined()) return position(context_->origin, node_.Mark());
  return context_->origin;
}

// A key path in a message: keys of an untrusted file may be long or hold line breaks.
void ConfigNode::fail(const std::string& message) const {
  throw ConfigError(where() + ": " + (path_.empty() ? "" : quoted_text(path_) + ": ") + message);
}

void ConfigNode::fail_at_key(const std::string& key, const std::string& message) const {
  const ConfigNode value = child(key);
  std::string where = value.where();
  if (!value.from_command_line() && is_map()) {
    for (const auto& kv : node_)
      if (kv.first.IsScalar() && kv.first.Scalar() == key)
        where = position(context_->origin, kv.first.Mark());
  }
  throw ConfigError(where + ": " + quoted_text(value.path()) + ": " + message);
}

std::string ConfigNode::as_string() const {
  if (!is_scalar()) fail("expected a string");
  return node_.Scalar();
}

double ConfigNode::as_double() const {
  if (!is_scalar()) fail("expected a number");
  const std::string text = strip_digit_separators(node_.Scalar());
  // YAML 1.1/1.2 spell infinity .inf / -.inf (any case); std::stod knows inf and infinity.
  // Neither is a setting, as NaN is not: every number rlrun takes is finite (a gravity of
  // .inf made Pendulum's episodes NaN), and a bound that may be open is written as null.
  std::string lower = text;
  std::transform(lower.begin(), lower.end(), lower.begin(), ::tolower);
  if (lower.find("nan") != std::string::npos)
    fail("expected a number, got '" + node_.Scalar() + "' (NaN is not a setting)");
  if (lower.find("inf") != std::string::npos)
    fail("expected a finite number, got '" + node_.Scalar() + "' (infinity is not a setting)");
  bool out_of_range = false;
  try {
    size_t used = 0;
    const double v = std::stod(text, &used);
    if (used == text.size() && std::isfinite(v)) return v;
  } catch (const std::out_of_range&) {
    out_of_range = true;
  } catch (const std::exception&) {
  }
  if (out_of_range) fail("number '" + node_.Scalar() + "' is out of the range of a double");
  fail("expected a number, got '" + node_.Scalar() + "'");
}

int64_t ConfigNode::as_int() const {
  if (!is_scalar()) fail("expected an integer");
  const std::string text = strip_digit_separators(node_.Scalar());
  // A plain integer is read exactly (seeds use all 63 bits).
  int64_t exact = 0;
  const char* begin = text.data() + (text.size() > 1 && text[0] == '+' ? 1 : 0);
  const auto [end, error] = std::from_chars(begin, text.data() + text.size(), exact);
  if (end == text.data() + text.size() && begin != end) {
    if (error == std::errc()) return exact;
    if (error == std::errc::result_out_of_range)
      fail("integer " + node_.Scalar() +
           " is out of range (at most 9223372036854775807 = 2^63 - 1)");
  }
  // Accept 1e5 and 100_000: rl-zoo files write timesteps that way.
  double v = std::numeric_limits<double>::quiet_NaN();
  try {
    size_t used = 0;
    const double parsed = std::stod(text, &used);
    if (used == text.size()) v = parsed;
  } catch (const std::exception&) {
  }
  if (std::isfinite(v) && std::floor(v) == v) {
    if (std::abs(v) < 9.0e15) return static_cast<int64_t>(v);
    fail("integer " + node_.Scalar() +
         " is out of range (above 9e15 write all digits; at most 2^63 - 1)");
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
  fail("expected true or false, got '" + (is_scalar() ? node_.Scalar() : "a non-scalar") + "'");
}

std::string yaml_override_text(const YAML::Node& node) {
  if (node.IsScalar()) return node.Scalar();
  YAML::Emitter out;
  out.SetMapFormat(YAML::Flow);
  out.SetSeqFormat(YAML::Flow);
  out << node;
  return out.c_str();
}

std::string yaml_double_quoted(const std::string& text) {
  YAML::Emitter out;
  out << YAML::DoubleQuoted << text;
  return out.c_str();
}

}  // namespace rlrun
