#pragma once
// An rl-baselines3-zoo hyperparameter file (hyperparams/<algo>.yml) and the entry the zoo
// would use for an env (rl_zoo3/exp_manager.py read_hyperparameters): the env id's own entry,
// else `default`, else an error. Gymnasium renamed LunarLander(Continuous)-v2 to -v3 (same
// task, bugs fixed) and the zoo renamed its entries with it: an old file's v2 entry serves
// the v3 env and the other way round, and the env trained is always the v3 one.
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

// The rlrun algorithm of a zoo file name (`ppo.yml` -> PPO), or "" when the name says none.
std::string algorithm_of_file(const std::string& path);

// Loads `path` and picks the entry for `env_id`, or the entry named `entry_name` when given
// (another env's settings for this env: `--entry PandaReach-v1` for GripperReach-v0).
// `algorithm` empty: from the file name. Throws ConfigError (file:line:col where there is one)
// for an unreadable file, an unknown algorithm, no entry of that name (did-you-mean), or no
// entry for the env and no `default`.
ZooEntry read_zoo_entry(const std::string& path, const std::string& env_id,
                        const std::string& algorithm, const std::string& entry_name = "");

}  // namespace rlrun::zoo
