#pragma once
// rl-zoo's `policy` and `policy_kwargs` -> rlrun's `algo.policy` map. SB3's policy keywords
// (stable_baselines3/common/policies.py ActorCriticPolicy, sac/policies.py, td3/policies.py,
// dqn/policies.py) become the rlrun keys of the same name; torch activation classes become
// rlrun's names; net_arch as a list, dict(pi=..., vf=.../qf=...) or SB3 < 1.8's
// [dict(pi=..., vf=...)]. Keywords without effect on an MLP policy (squash_output=False,
// share_features_extractor, normalize_images) are accepted and noted; any other keyword the
// algorithm's policy lacks is refused.
#include <string>
#include <vector>

#include <yaml-cpp/yaml.h>

#include "rlrun/core/config_node.hpp"

namespace rlrun::zoo {

// Checks `policy: 'MlpPolicy'` (and MultiInputPolicy). Throws ConfigError at the node for
// CnnPolicy and custom policies.
void check_policy_name(const ConfigNode& policy);

// `policy_kwargs` (a Python string or a YAML map) as the algo.policy map, with
// `policy_keys` the keys the rlrun algorithm's policy has. Problems throw ConfigError at the
// node; what was accepted without effect goes to `notes`.
YAML::Node translate_policy_kwargs(const ConfigNode& policy_kwargs,
                                   const std::vector<std::string>& policy_keys,
                                   const std::string& algorithm, std::vector<std::string>& notes);

}  // namespace rlrun::zoo
