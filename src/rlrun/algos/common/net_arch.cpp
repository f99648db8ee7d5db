#include "rlrun/algos/common/net_arch.hpp"

#include <string>
#include <vector>

namespace rlrun::net_arch_detail {

namespace {

void decode_sizes(const ConfigNode& n, std::vector<int>& out) {
  if (!n.is_sequence()) n.fail("expected a list of layer sizes, e.g. [64, 64] ([] for none)");
  rlrun::decode(n, out);
}

}  // namespace

void decode(const ConfigNode& n, const char* critic_key, bool critic_required, std::vector<int>& pi,
            std::vector<int>& critic) {
  if (n.is_sequence()) {
    decode_sizes(n, pi);
    critic = pi;
    return;
  }
  const std::string example = std::string(
                                  "a list [64, 64] (the same sizes for each network) or a map "
                                  "{pi: [64], ") +
                              critic_key + ": [64, 64]}";
  if (!n.is_map()) n.fail("expected " + example);
  const std::vector<std::string> valid = {"pi", critic_key};
  for (const std::string& key : n.keys()) {
    if (key == valid[0] || key == valid[1]) continue;
    // SB3's MlpExtractor would silently ignore the key (e.g. a `qf` in a PPO entry): refuse.
    n.fail_at_key(key, "unknown key '" + key + "'" + did_you_mean(key, valid) +
                           "; valid keys: pi, " + critic_key);
  }
  if (critic_required) {
    for (const std::string& key : valid)
      if (!n.has(key))
        n.fail("needs both pi and " + std::string(critic_key) +
               " (SB3's get_actor_critic_arch); '" + key + "' is missing");
  }
  // MlpExtractor: a key left out means no hidden layer for that network.
  pi.clear();
  critic.clear();
  if (n.has("pi")) decode_sizes(n.child("pi"), pi);
  if (n.has(critic_key)) decode_sizes(n.child(critic_key), critic);
}

YAML::Node encode(const char* critic_key, const std::vector<int>& pi,
                  const std::vector<int>& critic) {
  if (pi == critic) return rlrun::encode(pi);
  YAML::Node map(YAML::NodeType::Map);
  map["pi"] = rlrun::encode(pi);
  map[critic_key] = rlrun::encode(critic);
  map.SetStyle(YAML::EmitterStyle::Flow);
  return map;
}

void check(const ConfigNode& n, const char* critic_key, const std::vector<int>& pi,
           const std::vector<int>& critic, const Bounds& bounds) {
  if (n.is_sequence()) {
    check_value(n, pi, bounds);
    return;
  }
  if (n.has("pi")) check_value(n.child("pi"), pi, bounds);
  if (n.has(critic_key)) check_value(n.child(critic_key), critic, bounds);
}

}  // namespace rlrun::net_arch_detail
