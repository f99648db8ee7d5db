#include "rlrun/wrappers/shaping_term.hpp"

#include <algorithm>

namespace rlrun {

const std::vector<std::string>& shaping_term_types() {
  static const std::vector<std::string> types{"obs_above_for", "obs_below_for", "obs_abs",
                                              "action_sq", "constant"};
  return types;
}

void decode(const ConfigNode& n, ShapingTerm& out) {
  if (!n.is_map())
    n.fail("expected a term {type: ..., <params>}, e.g. {type: constant, value: -0.01}");
  const ConfigNode type = n.child("type");
  if (!type.defined())
    n.fail("missing `type` (one of obs_above_for, obs_below_for, obs_abs, action_sq, constant)");
  out = ShapingTerm{};
  out.type = type.as_string();
  const auto& types = shaping_term_types();
  if (std::find(types.begin(), types.end(), out.type) == types.end()) {
    std::string all;
    for (const auto& t : types) all += (all.empty() ? "" : ", ") + t;
    type.fail("unknown shaping term '" + out.type + "'" + did_you_mean(out.type, types) +
              "; valid types: " + all);
  }
  ConfigReader reader(n, {"type"});
  out.visit_fields(reader);
  reader.finish();
  if ((out.type == "obs_above_for" || out.type == "obs_below_for") && out.steps < 1)
    n.child("steps").fail("must be >= 1");
}

YAML::Node encode(const ShapingTerm& term) {
  ShapingTerm copy = term;
  ConfigWriter writer;
  copy.visit_fields(writer);
  YAML::Node node(YAML::NodeType::Map);
  node["type"] = term.type;
  for (const auto& kv : writer.node()) node[kv.first] = kv.second;
  node.SetStyle(YAML::EmitterStyle::Flow);
  return node;
}

}  // namespace rlrun
