#pragma once
// Hidden-layer activations of an Mlp. SB3's policy_kwargs.activation_fn is a torch class
// (nn.Tanh for PPO/A2C's MlpPolicy, nn.ReLU for SAC/TD3/DQN); rl-zoo YAML spells it "tanh" /
// "relu", which is what the experiment file uses.
#include <stdexcept>
#include <string>
#include <string_view>

namespace rlrun {

enum class Activation { kTanh, kReLU };

// "tanh" or "relu" (exact, lower case). Throws std::invalid_argument naming the valid values.
inline Activation parse_activation(std::string_view name) {
  if (name == "tanh") return Activation::kTanh;
  if (name == "relu") return Activation::kReLU;
  throw std::invalid_argument("unknown activation '" + std::string(name) +
                              "' (valid: tanh, relu)");
}

inline std::string_view activation_name(Activation act) {
  switch (act) {
    case Activation::kTanh:
      return "tanh";
    case Activation::kReLU:
      return "relu";
  }
  return "unknown";
}

}  // namespace rlrun
