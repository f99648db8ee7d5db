#pragma once
// `policy.net_arch` of the actor-critic algorithms: the hidden layer sizes of the actor (`pi`)
// and of the critic, which SB3 reads in two ways (stable_baselines3/common/torch_layers.py):
//  * a list `[64, 64]`: the same sizes for each network (SB3 >= 1.8: no shared layers);
//  * a map with a list per network: `{pi: [..], vf: [..]}` for PPO/A2C (MlpExtractor; a key
//    left out means no hidden layer, a linear head), `{pi: [..], qf: [..]}` for SAC, TD3 and
//    DDPG (get_actor_critic_arch, which asserts that both keys are there).
// Empty lists are allowed ([] = the head reads the features directly). Unknown keys are errors
// with a did-you-mean. The resolved config writes a list when both networks have the same
// sizes, a map otherwise; both read back to the same value.
//
// Reading: `config.net_arch.pi` (actor), `.vf` (value network, NetArchPiVf) or `.qf` (each
// Q-network, NetArchPiQf), all std::vector<int>.
#include <yaml-cpp/yaml.h>

#include <string>
#include <vector>

#include "rlrun/core/config_fields.hpp"

namespace rlrun {

// PPO, A2C: policy and value network (SB3 MlpExtractor). Aggregates: {{64, 64}, {64, 64}}.
struct NetArchPiVf {
  std::vector<int> pi;
  std::vector<int> vf;
  bool operator==(const NetArchPiVf&) const = default;
};

// SAC, TD3, DDPG: actor and each Q-network (SB3 get_actor_critic_arch).
struct NetArchPiQf {
  std::vector<int> pi;
  std::vector<int> qf;
  bool operator==(const NetArchPiQf&) const = default;
};

// The `rlrun list` lines of the field.
inline constexpr const char* kNetArchPiVfDoc =
    "hidden layer sizes: a list for the actor and the critic alike, or {pi: "
    "[..], vf: [..]}";
inline constexpr const char* kNetArchPiQfDoc =
    "hidden layer sizes: a list for the actor and each critic alike, or {pi: "
    "[..], qf: [..]}";

namespace net_arch_detail {

// Reads a list or a {pi, <critic_key>} map into the two size lists. `critic_required`: SB3's
// get_actor_critic_arch asserts both keys; MlpExtractor treats a missing one as [].
void decode(const ConfigNode& n, const char* critic_key, bool critic_required, std::vector<int>& pi,
            std::vector<int>& critic);
YAML::Node encode(const char* critic_key, const std::vector<int>& pi,
                  const std::vector<int>& critic);
// Checks each size against `bounds` at its own position (list or map form).
void check(const ConfigNode& n, const char* critic_key, const std::vector<int>& pi,
           const std::vector<int>& critic, const Bounds& bounds);

}  // namespace net_arch_detail

inline void decode(const ConfigNode& n, NetArchPiVf& out) {
  net_arch_detail::decode(n, "vf", false, out.pi, out.vf);
}
inline void decode(const ConfigNode& n, NetArchPiQf& out) {
  net_arch_detail::decode(n, "qf", true, out.pi, out.qf);
}
inline YAML::Node encode(const NetArchPiVf& v) { return net_arch_detail::encode("vf", v.pi, v.vf); }
inline YAML::Node encode(const NetArchPiQf& v) { return net_arch_detail::encode("qf", v.pi, v.qf); }
inline void check_value(const ConfigNode& n, const NetArchPiVf& v, const Bounds& bounds) {
  net_arch_detail::check(n, "vf", v.pi, v.vf, bounds);
}
inline void check_value(const ConfigNode& n, const NetArchPiQf& v, const Bounds& bounds) {
  net_arch_detail::check(n, "qf", v.pi, v.qf, bounds);
}

}  // namespace rlrun
