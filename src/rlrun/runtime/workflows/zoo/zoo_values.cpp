#include "rlrun/runtime/workflows/zoo/zoo_values.hpp"

#include "rlrun/core/quoted_text.hpp"

namespace rlrun::zoo {

namespace {

PyValue from_yaml_node(const YAML::Node& node) {
  PyValue v;
  if (node.IsNull()) return v;
  if (node.IsSequence()) {
    v.kind = PyValue::Kind::kList;
    for (const YAML::Node& item : node) v.items.push_back(from_yaml_node(item));
    return v;
  }
  if (node.IsMap()) {
    v.kind = PyValue::Kind::kDict;
    for (const auto& kv : node)
      v.entries.emplace_back(kv.first.Scalar(), from_yaml_node(kv.second));
    return v;
  }
  // A scalar: YAML's own types (true, 1e-3), else a string or a dotted name.
  const std::string text = node.Scalar();
  bool b = false;
  if (node.Tag() != "!" && YAML::convert<bool>::decode(node, b)) {
    v.kind = PyValue::Kind::kBool;
    v.boolean = b;
    return v;
  }
  if (node.Tag() != "!") {
    try {
      const PyValue number = parse_python_literal(text);
      if (number.kind == PyValue::Kind::kNumber) return number;
    } catch (const PythonLiteralError&) {
    }
  }
  v.kind = PyValue::Kind::kString;
  v.text = text;
  return v;
}

}  // namespace

PyValue python_value(const ConfigNode& node, const std::string& what) {
  if (!node.is_scalar()) return from_yaml_node(node.yaml());
  const std::string text = node.yaml().Scalar();
  try {
    return parse_python_literal(text);
  } catch (const PythonLiteralError& e) {
    // The text may be long (up to the file's 1 MiB) and hold newlines: quoted as one short line.
    node.fail(what + " \"" + quoted_text(text) + "\": at character " +
              std::to_string(e.offset() + 1) + ": " + e.what());
  }
}

YAML::Node to_yaml(const PyValue& value) {
  switch (value.kind) {
    case PyValue::Kind::kNone: return YAML::Node(YAML::NodeType::Null);
    case PyValue::Kind::kBool: return YAML::Node(value.boolean);
    case PyValue::Kind::kNumber: return YAML::Node(value.text);
    case PyValue::Kind::kString:
    case PyValue::Kind::kName: return YAML::Node(value.text);
    case PyValue::Kind::kList: {
      YAML::Node seq(YAML::NodeType::Sequence);
      for (const PyValue& item : value.items) seq.push_back(to_yaml(item));
      seq.SetStyle(YAML::EmitterStyle::Flow);
      return seq;
    }
    case PyValue::Kind::kDict: {
      YAML::Node map(YAML::NodeType::Map);
      for (const auto& [key, item] : value.entries) map[key] = to_yaml(item);
      map.SetStyle(YAML::EmitterStyle::Flow);
      return map;
    }
  }
  return YAML::Node();
}

}  // namespace rlrun::zoo
