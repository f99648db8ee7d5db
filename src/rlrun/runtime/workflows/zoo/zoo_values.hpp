#pragma once
// The zoo's Python-valued settings (policy_kwargs, normalize, env_wrapper and callback
// arguments) as PyValue trees, whether the file writes them as a Python string or as YAML,
// and PyValue -> YAML for the experiment file.
#include <string>

#include <yaml-cpp/yaml.h>

#include "rlrun/core/config_node.hpp"
#include "rlrun/runtime/workflows/zoo/python_literal.hpp"

namespace rlrun::zoo {

// A scalar string is parsed as a Python literal (errors: ConfigError at the node, with the
// character); a YAML map or list is converted. `what` names the setting in messages.
PyValue python_value(const ConfigNode& node, const std::string& what);

// None -> null, numbers as written, lists in flow style, dicts as maps.
YAML::Node to_yaml(const PyValue& value);

}  // namespace rlrun::zoo
