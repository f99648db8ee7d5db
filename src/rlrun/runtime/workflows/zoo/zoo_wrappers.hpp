#pragma once
// rl-zoo's `env_wrapper` and `callback` (rl_zoo3/utils.py get_wrapper_class,
// get_callback_list): a class path, or a list of class paths and {class path: kwargs}. Known
// classes map to rlrun's (docs/zoo.md); any other is refused at its line and column.
#include <string>
#include <vector>

#include <yaml-cpp/yaml.h>

#include "rlrun/core/config_node.hpp"

namespace rlrun::zoo {

// `env` is (a handle to) the experiment's env section: wrappers and max_episode_steps are added;
// `registered_limit` the env's own time limit (0: none). Throws ConfigError.
void translate_env_wrappers(const ConfigNode& env_wrapper, YAML::Node env, int registered_limit,
                            std::vector<std::string>& notes);

// Adds to `experiment` the sections the callbacks map to. `n_envs` converts SB3's per-call
// frequencies to rlrun's total env steps. Throws ConfigError.
void translate_callbacks(const ConfigNode& callback, YAML::Node& experiment, int n_envs,
                         std::vector<std::string>& notes);

}  // namespace rlrun::zoo
