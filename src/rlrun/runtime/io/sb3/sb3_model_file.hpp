#pragma once
// Stable-Baselines3 model files (`model.save("ppo_cartpole")`: SB3 2.x's save_to_zip_file in
// stable_baselines3/common/save_util.py) read as rlrun model files, so that `rlrun eval`,
// `record`, `export` and the Python package's rlrun.load take them (docs/sb3_models.md). The
// zip holds
//   data                      JSON of the algorithm's attributes; those JSON cannot hold
//                             (the policy class, the spaces, schedules) as
//                             {":type:": ..., ":serialized:": base64 of a cloudpickle, plus
//                             the JSON-able attributes of the object}
//   policy.pth                torch.save(policy.state_dict()) (core/torch_state_dict.hpp)
//   pytorch_variables.pth     other tensors (SAC's log_ent_coef)
//   policy.optimizer.pth, _stable_baselines3_version, system_info.txt: not read
// SB3 files are untrusted like any model file (docs/security.md): nothing in them is run — the
// pickles go through core/pickle_reader.hpp with allowlists (the policy class is only compared
// with SB3's names, spaces through runtime/io/sb3/sb3_spaces.hpp), every member is read with a
// bound, and the weights must be finite.
// The file does not say its algorithm's class or its env: the algorithm follows from the
// policy class and the hyperparameters `data` holds (PPO has clip_range, A2C not; DDPG is TD3
// with policy_delay 1 and no target noise), the env id is the caller's (`--env ID`).
#include <string>

#include <yaml-cpp/yaml.h>

#include "rlrun/runtime/io/model_file.hpp"

namespace rlrun {

// A zip with SB3's `data` and `policy.pth` members and without rlrun's meta.json. False for
// anything else, including files that are not zips (their reader says what is wrong).
bool is_sb3_model_file(const std::string& path);

// The whole file as an rlrun ModelFile: meta (algorithm, `env_id`, the spaces), a config.yaml
// that builds the same policy (networks from the tensors' shapes, activation_fn from
// policy_kwargs; RecurrentPPO's LSTM sizes and critic kind) and the tensors under rlrun's
// names (the same as SB3's state_dict names but for DQN's q_net.q_net.* -> q_net.*). SB3's
// PPO, A2C, DQN, SAC, TD3, DDPG and sb3-contrib's QR-DQN, TQC, MaskablePPO and RecurrentPPO.
// Throws RuntimeFailure naming the file and the reason:
// a policy rlrun does not read (CnnPolicy, a custom features extractor), a space it does
// not hold, a pickle naming anything outside its allowlist, a malformed member.
// `env_section` (untrusted, like the file): env settings the model was trained with that the
// file does not hold — the `wrappers` (and `max_episode_steps`) an rl-zoo run folder's
// config.yml names (runtime/workflows/zoo/zoo_run_folder.hpp) — written into its config.yml.
ModelFile read_sb3_model(const std::string& path, const std::string& env_id,
                         const YAML::Node& env_section = YAML::Node());

}  // namespace rlrun
