#pragma once
// `rlrun export --format sb3`: an rlrun model as a Stable-Baselines3 2.x model file that SB3's
// `PPO.load(path)` (A2C, DQN, SAC, TD3, DDPG likewise) opens and whose `predict` acts as
// rlrun's policy does (docs/sb3_models.md, "Writing SB3 files"). The members are those of
// SB3's save_to_zip_file (stable_baselines3/common/save_util.py) for the algorithm's
// _get_torch_save_params:
//   data                         JSON; what JSON cannot hold is {":type:", ":serialized:"},
//                                the base64 of a pickle written here (core/pickle_writer.hpp):
//                                the policy class (a reference to SB3's class), the spaces
//                                (runtime/io/sb3/sb3_spaces.hpp), policy_kwargs (which name
//                                torch classes), train_freq (a tuple)
//   policy.pth                   the policy's state_dict (core/torch_file_writer.hpp): rlrun's
//                                tensors already have SB3's names (DQN's q_net nests once more)
//   <optimizer>.pth              each optimizer's state_dict with its param groups (lr, eps,
//                                ... as SB3 builds it) and no per-parameter state: SB3 then
//                                starts Adam's moments afresh, as after a new optimizer
//   pytorch_variables.pth        SAC's log_ent_coef (or ent_coef_tensor)
//   _stable_baselines3_version   "2.4.1": the version whose format this is
//   system_info.txt              who wrote it
// Written from the model's resolved configuration: its hyperparameters under SB3's names,
// schedules as their initial value (SB3 would pickle a function: code), n_envs, num_timesteps.
// sb3-contrib's QR-DQN, TQC, TRPO, MaskablePPO and RecurrentPPO are written too (DQN's, SAC's
// and PPO's files with their policy classes and settings; RecurrentPPO's LSTM tensors).
// Refused with the reason: algorithms neither has a class for here (ARS, CrossQ, ...), CNN or
// other non-flatten features extractors.
#include <string>
#include <vector>

#include "rlrun/core/zip_archive.hpp"
#include "rlrun/runtime/io/model_loader.hpp"

namespace rlrun {

// The version of SB3's format written (its `_stable_baselines3_version`).
inline constexpr const char* kSb3FormatVersion = "2.4.1";

struct Sb3ModelExport {
  ZipMembers members;
  std::string load_class;  // "stable_baselines3.PPO", "sb3_contrib.RecurrentPPO", ...
  // What SB3's file cannot carry from this model (one line each): env wrappers that change
  // what the policy sees, schedules, action noise.
  std::vector<std::string> notes;
};

// Throws RuntimeFailure naming the model and the reason it cannot be written.
Sb3ModelExport sb3_model_export(const LoadedModel& model);

}  // namespace rlrun
