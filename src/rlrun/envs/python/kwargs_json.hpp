#pragma once
// `env.kwargs` of a Python env as the JSON the worker passes to the env's constructor:
// YAML's plain scalars become JSON's null / bool / int / float as YAML 1.2's core schema
// reads them (what yaml.safe_load gives a Python user), quoted scalars stay strings, maps
// and lists nest.
#include <yaml-cpp/yaml.h>

#include <string>

namespace rlrun {

// Throws std::invalid_argument for a map key that is not a scalar.
std::string kwargs_json(const YAML::Node& kwargs);

}  // namespace rlrun
