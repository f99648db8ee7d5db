#pragma once
// rl-baselines3-zoo names a run's folder <env>_<n> (logs/<algo>/CartPole-v1_1,
// rl_zoo3/exp_manager.py): the env id is the name without its trailing _<digits>. Read where
// a model's VecNormalize statistics are looked for (sb3_vec_normalize.cpp) and where a run
// folder is played (runtime/workflows/zoo/zoo_run_folder.cpp).
#include <string>

namespace rlrun {

// "CartPole-v1_1" -> "CartPole-v1"; "" when the name does not end in _<digits>.
inline std::string rl_zoo_folder_env(const std::string& folder_name) {
  const std::size_t underscore = folder_name.rfind('_');
  if (underscore == std::string::npos || underscore == 0 || underscore + 1 == folder_name.size())
    return "";
  if (folder_name.find_first_not_of("0123456789", underscore + 1) != std::string::npos) return "";
  return folder_name.substr(0, underscore);
}

}  // namespace rlrun
