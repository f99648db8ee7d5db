#pragma once
// An rl-baselines3-zoo run folder, as `python -m rl_zoo3.train` leaves it
// (logs/<algo>/<env>_<n>/) and DLR-RM/rl-trained-agents publishes it:
//   <env>.zip            the model (SB3's model.save)
//   best_model.zip       the best model of the evaluations, when there were any
//   <env>/config.yml     the hyperparameters used; <env>/vecnormalize.pkl the VecNormalize
//                        statistics (read beside the model: runtime/io/sb3/sb3_vec_normalize.hpp)
// `rlrun eval --zoo-model DIR` plays it as `python -m rl_zoo3.enjoy --algo <algo> --env <env>
// -f logs/` does: the model of the folder on the folder's env (rlrun's id for it), wrapped in
// the config.yml's `env_wrapper` (translated as `rlrun zoo import` translates it:
// zoo_wrappers.hpp) and `frame_stack` (FrameStack, SB3's layout), with the statistics frozen.
#include <yaml-cpp/yaml.h>

#include <cstdint>
#include <string>
#include <vector>

#include "rlrun/runtime/components/registry.hpp"

namespace rlrun::zoo {

struct ZooRunFolder {
  std::string model_path;
  std::string env_id;      // rlrun's id of the folder's env
  YAML::Node env_section;  // `wrappers`, `max_episode_steps` (env_wrapper), `kwargs` (args.yml)
  std::vector<std::string> notes;  // what of the zoo's config.yml is not applied, and why
};

// Which model of the folder, as rl_zoo3.enjoy's --load-best, --load-checkpoint N and
// --load-last-checkpoint choose (rl_zoo3/enjoy.py): <env>.zip by default, best_model.zip
// (EvalCallback's), rl_model_<N>_steps.zip (CheckpointCallback's), or the one of those with
// the most steps.
struct ZooModelChoice {
  bool best = false;
  int64_t checkpoint = 0;  // > 0: that checkpoint
  bool last_checkpoint = false;
};

// `dir` must be named <env>_<n> and hold the chosen model. Throws UsageError naming what is
// missing. config.yml is untrusted: what it names that rlrun does not translate becomes a
// note, never an error (the model's observation check decides).
ZooRunFolder find_zoo_run_folder(const std::string& dir, const ZooModelChoice& choice,
                                 const Registry& registry);

}  // namespace rlrun::zoo
