#pragma once
// An rl-baselines3-zoo run folder, as `python -m rl_zoo3.train` leaves it
// (logs/<algo>/<env>_<n>/) and DLR-RM/rl-trained-agents publishes it:
//   <env>.zip            the model (SB3's model.save)
//   best_model.zip       the best model of the evaluations, when there were any
//   <env>/config.yml     the hyperparameters used; <env>/vecnormalize.pkl the VecNormalize
//                        statistics (read beside the model: runtime/io/sb3/sb3_vec_normalize.hpp)
// `rlrun eval --zoo-model DIR` plays it as `python -m rl_zoo3.enjoy --algo <algo> --env <env>
// -f logs/` does: the model of the folder on the folder's env (rlrun's id for it), with the
// statistics frozen.
#include <string>
#include <vector>

namespace rlrun::zoo {

struct ZooRunFolder {
  std::string model_path;
  std::string env_id;              // rlrun's id of the folder's env
  std::vector<std::string> notes;  // what the zoo's config.yml asks that rlrun does not apply
};

// `dir` must be named <env>_<n> and hold <env>.zip (or best_model.zip with `best`). Throws
// UsageError naming what is missing.
ZooRunFolder find_zoo_run_folder(const std::string& dir, bool best);

}  // namespace rlrun::zoo
