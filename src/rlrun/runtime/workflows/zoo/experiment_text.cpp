#include "rlrun/runtime/workflows/zoo/experiment_text.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <ctime>
#include <vector>

#include "rlrun/core/config_node.hpp"
#include "rlrun/core/errors.hpp"
#include "rlrun/core/quoted_text.hpp"

namespace rlrun::zoo {

namespace {

// Header lines may be longer than a message's quote: file paths, notes naming a class.
constexpr std::size_t kMaxCommentBytes = 1000;

// A copy without the zoo file's tags (!!float) and aliases, with lists in flow style.
YAML::Node clean(const YAML::Node& node) {
  if (node.IsSequence()) {
    YAML::Node seq(YAML::NodeType::Sequence);
    for (const YAML::Node& item : node) seq.push_back(clean(item));
    seq.SetStyle(node.Style() == YAML::EmitterStyle::Block && seq.size() > 0 && seq[0].IsMap()
                     ? YAML::EmitterStyle::Block
                     : YAML::EmitterStyle::Flow);
    return seq;
  }
  if (node.IsMap()) {
    YAML::Node map(YAML::NodeType::Map);
    for (const auto& kv : node) map.force_insert(kv.first.Scalar(), clean(kv.second));
    map.SetStyle(node.Style());
    return map;
  }
  if (node.IsNull()) return YAML::Node(YAML::NodeType::Null);
  return YAML::Node(node.Scalar());
}

// Counts the zoo writes as floats (`n_timesteps: !!float 1e6`), written as integers.
void write_counts_as_integers(YAML::Node experiment) {
  const std::pair<const char*, const char*> counts[] = {
      {"run", "total_timesteps"}, {"algo", "buffer_size"}, {"algo", "learning_starts"}};
  for (const auto& [section, key] : counts) {
    YAML::Node node = experiment[section][key];
    if (!node || !node.IsScalar()) continue;
    char* end = nullptr;
    const std::string text = node.Scalar();
    const double value = std::strtod(text.c_str(), &end);
    if (end == text.c_str() + text.size() && std::floor(value) == value && std::fabs(value) < 9e15)
      experiment[section][key] = static_cast<int64_t>(value);
  }
}

std::string today() {
  const std::time_t now = std::chrono::system_clock::to_time_t(std::chrono::system_clock::now());
  std::tm utc{};
  gmtime_r(&now, &utc);
  char buffer[16];
  std::strftime(buffer, sizeof buffer, "%Y-%m-%d", &utc);
  return buffer;
}

std::vector<std::string> header_lines(const ZooImport& imported) {
  const ZooEntry& s = imported.source;
  std::vector<std::string> lines{
      "Imported by `rlrun zoo import` (rlrun " RLRUN_VERSION ") on " + today() +
          " from the rl-baselines3-zoo",
      "hyperparameters " + s.file + ", entry '" + s.entry_name + "' (" + s.algorithm + ")" +
          (s.entry_name == "default" ? ": the file has no entry for " + s.env_id : "") + ".",
      "Evaluation as rl-zoo's train.py defaults: every 25000 env steps, 5 episodes, "
      "deterministic."};
  for (const std::string& note : imported.notes) lines.push_back("Note: " + note);
  for (const std::string& assignment : imported.overrides)
    lines.push_back("Set on the command line: --set " + assignment);
  return lines;
}

// A scalar, double-quoted where a plain one would read back as something else: a control
// character (yaml-cpp writes a carriage return raw in a plain scalar), or `<<` as a key (a merge
// key on reading). Null-like strings ("null", "~", "") yaml-cpp quotes itself.
void emit_scalar(YAML::Emitter& out, const std::string& text, bool is_key) {
  const bool control = std::any_of(text.begin(), text.end(), [](char c) {
    return static_cast<unsigned char>(c) < 0x20 || c == 0x7F;
  });
  if (control || (is_key && text == "<<")) out << YAML::DoubleQuoted;
  out << text;
}

// `node` through the emitter, value by value (no anchors or aliases), in its flow or block style.
void emit(YAML::Emitter& out, const YAML::Node& node) {
  if (!node.IsDefined() || node.IsNull()) {
    out << YAML::Null;
    return;
  }
  if (node.IsScalar()) {
    emit_scalar(out, node.Scalar(), false);
    return;
  }
  out << (node.Style() == YAML::EmitterStyle::Flow ? YAML::Flow : YAML::Block);
  if (node.IsSequence()) {
    out << YAML::BeginSeq;
    for (const YAML::Node& item : node) emit(out, item);
    out << YAML::EndSeq;
    return;
  }
  out << YAML::BeginMap;
  for (const auto& kv : node) {
    out << YAML::Key;
    emit_scalar(out, kv.first.Scalar(), true);
    out << YAML::Value;
    emit(out, kv.second);
  }
  out << YAML::EndMap;
}

}  // namespace

YAML::Node experiment_tree(const ZooImport& imported) {
  YAML::Node ordered(YAML::NodeType::Map);
  for (const char* section : {"run", "env", "algo", "eval", "checkpoint"})
    if (imported.experiment[section]) ordered[section] = clean(imported.experiment[section]);
  write_counts_as_integers(ordered);
  return ordered;
}

std::string experiment_text(const ZooImport& imported) {
  YAML::Emitter out;
  out.SetIndent(2);
  out.SetOutputCharset(YAML::EscapeNonAscii);
  // One comment per line; after the last one the emitter starts the map on a line of its own.
  const std::vector<std::string> header = header_lines(imported);
  for (std::size_t i = 0; i < header.size(); ++i) {
    if (i > 0) out << YAML::Newline;
    out << YAML::Comment(quoted_text(header[i], kMaxCommentBytes));
  }
  emit(out, experiment_tree(imported));
  if (!out.good())
    throw ConfigError(imported.source.file +
                      ": cannot write the experiment: " + out.GetLastError());
  std::string text = std::string(out.c_str()) + "\n";
  if (text.size() > kMaxConfigBytes)
    throw ConfigError(imported.source.file + ": the experiment would be larger than " +
                      std::to_string(kMaxConfigBytes >> 20) +
                      " MiB, more than rlrun reads in an experiment file (an entry takes a few "
                      "hundred bytes; do aliases repeat a large value?)");
  return text;
}

}  // namespace rlrun::zoo
