#pragma once
// `policy.activation_fn` as a config value: the lower-case name (`relu`) or torch's class as
// rl-zoo writes it (`nn.ReLU`); both read to the same Activation, and the resolved config
// writes the lower-case name (nn/activation.hpp has the table).
#include <yaml-cpp/yaml.h>

#include <string>
#include <vector>

#include "rlrun/core/config_fields.hpp"
#include "rlrun/nn/activation.hpp"

namespace rlrun {

// The `rlrun list` line of every algorithm's activation_fn.
inline constexpr const char* kActivationFnDoc =
    "activation between hidden layers: tanh, relu, elu, leaky_relu, gelu (or torch's nn.Tanh, "
    "nn.ReLU, nn.ELU, nn.LeakyReLU, nn.GELU; gelu is the exact erf form, torch's default)";

inline void decode(const ConfigNode& n, Activation& out) {
  const std::string name = n.as_string();
  if (const auto act = find_activation(name)) {
    out = *act;
    return;
  }
  std::vector<std::string> valid;
  for (const auto& s : kActivationSpellings) valid.emplace_back(s.name);
  for (const auto& s : kActivationSpellings) valid.emplace_back(s.torch_name);
  n.fail("unknown activation '" + name + "'" + did_you_mean(name, valid) +
         "; valid: " + valid_activation_names());
}

inline YAML::Node encode(Activation act) { return YAML::Node(std::string(activation_name(act))); }

}  // namespace rlrun
