#pragma once
// Hidden-layer activations of an Mlp. SB3's policy_kwargs.activation_fn is a torch class
// (nn.Tanh for PPO/A2C's MlpPolicy, nn.ReLU for SAC/TD3/DQN); rl-zoo's hyperparameter files
// write the class (`activation_fn=nn.ReLU`), rl-zoo-style YAML often the lower-case name. Both
// are accepted; the lower-case name is the canonical one written into resolved configs. Each
// activation has torch's default constructor arguments, which SB3 uses (it calls
// activation_fn() with no argument): nn.ELU(alpha=1.0), nn.LeakyReLU(negative_slope=0.01),
// nn.GELU(approximate='none'), the exact gelu(x) = x Phi(x) = x (1 + erf(x / sqrt(2))) / 2 of
// https://pytorch.org/docs/stable/generated/torch.nn.GELU.html (not its tanh approximation;
// rl-zoo's PPO CarRacing-v3 entry uses it).
#include <array>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>

namespace rlrun {

enum class Activation { kTanh, kReLU, kELU, kLeakyReLU, kGELU };

// torch.nn.LeakyReLU's default negative_slope.
inline constexpr float kLeakyReLUSlope = 0.01f;

struct ActivationSpelling {
  Activation act;
  std::string_view name;        // canonical: "leaky_relu"
  std::string_view torch_name;  // "nn.LeakyReLU"
};
inline constexpr std::array<ActivationSpelling, 5> kActivationSpellings = {{
    {Activation::kTanh, "tanh", "nn.Tanh"},
    {Activation::kReLU, "relu", "nn.ReLU"},
    {Activation::kELU, "elu", "nn.ELU"},
    {Activation::kLeakyReLU, "leaky_relu", "nn.LeakyReLU"},
    {Activation::kGELU, "gelu", "nn.GELU"},
}};

// The activation a name or torch spelling means (exact case), or nothing.
inline std::optional<Activation> find_activation(std::string_view name) {
  for (const auto& s : kActivationSpellings)
    if (name == s.name || name == s.torch_name) return s.act;
  return std::nullopt;
}

inline std::string_view activation_name(Activation act) {
  for (const auto& s : kActivationSpellings)
    if (s.act == act) return s.name;
  return "unknown";
}

// "tanh, relu, ... (or torch's nn.Tanh, nn.ReLU, ...)": the valid names, for error messages.
inline std::string valid_activation_names() {
  std::string names, torch_names;
  for (const auto& s : kActivationSpellings) {
    names += (names.empty() ? "" : ", ") + std::string(s.name);
    torch_names += (torch_names.empty() ? "" : ", ") + std::string(s.torch_name);
  }
  return names + " (or torch's " + torch_names + ")";
}

// Throws std::invalid_argument naming the valid values.
inline Activation parse_activation(std::string_view name) {
  if (const auto act = find_activation(name)) return *act;
  throw std::invalid_argument("unknown activation '" + std::string(name) +
                              "' (valid: " + valid_activation_names() + ")");
}

}  // namespace rlrun
