#pragma once
// rl-zoo's `policy` and `policy_kwargs` -> rlrun's `algo.policy` map. SB3's policy keywords
// (stable_baselines3/common/policies.py ActorCriticPolicy, sac/policies.py, td3/policies.py,
// dqn/policies.py) become the rlrun keys of the same name; torch activation classes become
// rlrun's names; net_arch as a list, dict(pi=..., vf=.../qf=...) or SB3 < 1.8's
// [dict(pi=..., vf=...)]. CnnPolicy becomes features_extractor_class: NatureCNN with SB3's
// default net_arch for it unless policy_kwargs sets one ([] for PPO, A2C and DQN; [256, 256]
// for SAC, TD3, DDPG and TQC); features_extractor_kwargs' features_dim, normalize_images and
// share_features_extractor carry over. Keywords without
// effect on an MLP policy (squash_output=False; share_features_extractor and normalize_images
// where the algorithm has no CNN) are accepted and noted; any other keyword the algorithm's
// policy lacks is refused.
#include <string>
#include <vector>

#include <yaml-cpp/yaml.h>

#include "rlrun/core/config_node.hpp"

namespace rlrun::zoo {

// Checks `policy: 'MlpPolicy'` (and MultiInputPolicy, and CnnPolicy for the algorithms that
// have it: PPO, A2C, DQN, SAC, TD3, DDPG, TQC); true for CnnPolicy. Throws ConfigError at the node for custom policies
// and a CnnPolicy of another algorithm.
bool check_policy_name(const ConfigNode& policy, const std::string& algorithm);

// `policy_kwargs` (a Python string or a YAML map) as the algo.policy map, with
// `policy_keys` the keys the rlrun algorithm's policy has. Problems throw ConfigError at the
// node; what was accepted without effect goes to `notes`.
YAML::Node translate_policy_kwargs(const ConfigNode& policy_kwargs,
                                   const std::vector<std::string>& policy_keys,
                                   const std::string& algorithm, std::vector<std::string>& notes);

}  // namespace rlrun::zoo
