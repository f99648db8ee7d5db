#pragma once
// An rl-baselines3-zoo hyperparameter file (hyperparams/<algo>.yml) and the entry the zoo
// would use for an env (rl_zoo3/exp_manager.py read_hyperparameters): the env id's own entry,
// else `default`, else an error. Gymnasium renamed LunarLander(Continuous)-v2 to -v3 (same
// task, bugs fixed) and the zoo renamed its entries with it: an old file's v2 entry serves
// the v3 env and the other way round, and the env trained is always the v3 one. rlrun's
// Gymnasium envs (`gymnasium:LunarLander-v3`) take the entry of the Gymnasium id.
//
// A zoo file may come from anyone (docs/security.md): it is loaded as untrusted text (the
// config bounds, merge keys resolved), an entry may nest at most 16 levels and hold at most
// 64 KiB of text and 10 000 values with aliases expanded, and errors quote its text as one
// bounded line each (core/quoted_text.hpp).
#include <string>

#include "rlrun/core/config_node.hpp"

namespace rlrun::zoo {

struct ZooEntry {
  std::string file;        // the hyperparameter file
  std::string algorithm;   // rlrun's id: PPO, A2C, DQN, SAC, TD3, DDPG, TQC
  std::string entry_name;  // the key of the entry used ("default" when it was)
  std::string env_id;      // the rlrun env to train
  ConfigNode node;         // the entry (positions in `file`)
};

// rlrun's id of an env the zoo names by a retired Gymnasium id (LunarLander-v2 -> -v3, the
// MuJoCo tasks' -v2/-v3 -> -v4); any other id as it is.
std::string current_env_id(const std::string& zoo_env_id);

// The rlrun algorithm of a zoo file name (`ppo.yml` -> PPO), or "" when the name says none.
std::string algorithm_of_file(const std::string& path);

// Loads `path` and picks the entry for `env_id`, or the entry named `entry_name` when given
// (another env's settings for this env: `--entry PandaReach-v1` for GripperReach-v0).
// `algorithm` empty: from the file name. Throws ConfigError (file:line:col where there is one)
// for an unreadable file, an algorithm rlrun does not have (named: trpo.yml is sb3-contrib's
// TRPO), no entry of that name (did-you-mean), no entry for the env and no `default`, or an
// entry over the bounds above.
ZooEntry read_zoo_entry(const std::string& path, const std::string& env_id,
                        const std::string& algorithm, const std::string& entry_name = "");

}  // namespace rlrun::zoo
