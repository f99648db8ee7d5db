#pragma once
// A YAML node that remembers where it came from, so every config error can name the file,
// line, column and key path ("configs/x.yaml:7:3: algo.n_stps: unknown key; did you mean
// 'n_steps'?"). Values set with `--set key=value` are reported as coming from the command line.
//
// Every node also knows whether its text is the user's own (an experiment file named on the
// command line, or a `--set`) or came from a file rlrun does not trust (the config.yaml inside
// a model file or checkpoint, a run directory's config.yaml, a sweep manifest's configs):
// docs/security.md. Field types that start programs or write files refuse values from
// untrusted text (core/trusted_values.hpp).
//
// Loading bounds the input before anything else reads it: at most kMaxConfigBytes of text,
// one YAML document, at most kMaxConfigNodes nodes counted with aliases expanded (so later
// walks are bounded too), and no key twice in one map (YAML tools disagree on which one wins).
// YAML merge keys (`<<: *defaults`, `<<: [*a, *b]`; yaml.org/type/merge.html) are then
// resolved as PyYAML resolves them: keys written in the map win, and of several merged maps
// the earlier; merging never adds nodes to the count above.
#include <yaml-cpp/yaml.h>

#include <memory>
#include <new>
#include <string>
#include <vector>

namespace rlrun {

// Where a config's text came from (docs/security.md). kAccepted: untrusted text
// the user accepted as a whole for one command (`--trust`, `rlrun.load(..., trust=True)`): it
// may name what the user's own text may, and each value a --set would otherwise have had to
// vouch for is printed before use (core/trusted_values.hpp).
enum class ConfigTrust { kUser, kUntrusted, kAccepted };

inline constexpr std::size_t kMaxConfigBytes = 1 << 20;  // experiment files are a few KB
inline constexpr std::size_t kMaxConfigNodes = 100000;

class ConfigNode {
 public:
  ConfigNode() = default;
  // YAML::Node's operator= assigns the VALUE into the referenced node, and reset() throws for
  // an absent key's node; a ConfigNode is a handle, so assignment re-constructs the node.
  ConfigNode(const ConfigNode& other) = default;
  ConfigNode& operator=(const ConfigNode& other) {
    if (this != &other) {
      node_.~Node();
      new (&node_) YAML::Node(other.node_);
      context_ = other.context_;
      path_ = other.path_;
    }
    return *this;
  }
  // Parses a YAML file; a syntax error is a ConfigError naming file:line:col, and so is a
  // file over the bounds above, a second document or a repeated key.
  static ConfigNode load_file(const std::string& path, ConfigTrust trust = ConfigTrust::kUser);
  // Parses YAML text; `origin` names it in messages (e.g. "model.zip:config.yaml").
  static ConfigNode load_string(const std::string& text, const std::string& origin,
                                ConfigTrust trust = ConfigTrust::kUser);
  // Wraps an existing node (built in code, or translated from a file of `trust`); positions
  // are the node's own.
  static ConfigNode from_yaml(YAML::Node node, const std::string& origin, std::string path = "",
                              ConfigTrust trust = ConfigTrust::kUser);

  // Applies `--set a.b.c=value`: the value is parsed as YAML, missing maps are created.
  void apply_override(const std::string& assignment);
  // Marks the value at `key_path` as the user's own, as a `--set` value is: code put it there
  // from the user's command line in another form (`rlrun train --zoo ... --env ID`). Messages
  // about it name `shown` as its place.
  void vouch_for(const std::string& key_path, const std::string& shown);

  const YAML::Node& yaml() const { return node_; }
  YAML::Node& yaml() { return node_; }
  const std::string& path() const { return path_; }
  const std::string& origin() const { return context_->origin; }
  // True for the user's own text (a trusted file, a value typed with --set) and for text the
  // user accepted as a whole.
  bool trusted() const { return context_->trust != ConfigTrust::kUntrusted || from_command_line(); }
  // True when the value is trusted only because the user accepted the whole text: rlrun
  // prints it before using it.
  bool accepted_as_a_whole() const {
    return context_->trust == ConfigTrust::kAccepted && !from_command_line();
  }
  // The command's option that accepts this text as a whole ("--trust"), named in refusals and
  // announcements; "" when the command has none. Shared by every node of the text.
  const std::string& trust_option() const { return context_->trust_option; }
  void set_trust_option(std::string option) const { context_->trust_option = std::move(option); }
  bool from_command_line() const;
  bool defined() const { return node_.IsDefined() && !node_.IsNull(); }
  // Absent keys give "invalid" yaml-cpp nodes whose Type() throws: check IsDefined() first.
  bool is_map() const { return node_.IsDefined() && node_.IsMap(); }
  bool is_sequence() const { return node_.IsDefined() && node_.IsSequence(); }
  bool is_scalar() const { return node_.IsDefined() && node_.IsScalar(); }
  std::size_t size() const { return node_.IsDefined() ? node_.size() : 0; }

  bool has(const std::string& key) const;
  // Child of a map (undefined node if absent) and of a sequence.
  ConfigNode child(const std::string& key) const;
  ConfigNode at(std::size_t index) const;
  // A copy of this map without `key` (same origin, trust and positions).
  ConfigNode without(const std::string& key) const;
  std::vector<std::string> keys() const;

  // "file:line:col" of this node, "--set path=value" for a command-line override, or the
  // origin alone when the position is unknown.
  std::string where() const;
  // Throws ConfigError "<where>: <path>: <message>".
  [[noreturn]] void fail(const std::string& message) const;
  // Same, positioned at the KEY `key` of this map (for unknown keys: the key is the typo).
  [[noreturn]] void fail_at_key(const std::string& key, const std::string& message) const;

  // Scalar conversions with clear errors ("expected an integer, got 'abc'").
  std::string as_string() const;
  double as_double() const;
  int64_t as_int() const;
  bool as_bool() const;

 private:
  struct Context {
    std::string origin;  // file name or description
    ConfigTrust trust = ConfigTrust::kUser;
    std::string trust_option;                 // e.g. "--trust" (see trust_option())
    std::vector<std::string> override_paths;  // paths set from the command line
    std::vector<std::string> override_shown;  // where each came from: "--set path=value"
  };
  ConfigNode(YAML::Node node, std::shared_ptr<Context> context, std::string path)
      : node_(std::move(node)), context_(std::move(context)), path_(std::move(path)) {}

  YAML::Node node_;
  std::shared_ptr<Context> context_ = std::make_shared<Context>();
  std::string path_;
};

// Closest candidate by edit distance, or "" if none is plausibly meant.
std::string closest_name(const std::string& name, const std::vector<std::string>& candidates);
// " (did you mean 'x'?)" or "" — appended to unknown-name messages.
std::string did_you_mean(const std::string& name, const std::vector<std::string>& candidates);

// A YAML value as the text of a `--set key=<text>` override: a scalar as written, a list or map
// in flow style ("[64, 64]", "{pi: [64], vf: [64]}").
std::string yaml_override_text(const YAML::Node& node);
// `text` as a YAML double-quoted scalar, read back as exactly `text` (paths, names).
std::string yaml_double_quoted(const std::string& text);

}  // namespace rlrun
