#include "rlrun/runtime/run/init_from.hpp"

#include "rlrun/core/errors.hpp"
#include "rlrun/core/plural.hpp"
#include "rlrun/runtime/experiment/env_statistics.hpp"
#include "rlrun/runtime/io/model_budget.hpp"
#include "rlrun/runtime/io/model_file.hpp"
#include "rlrun/runtime/io/sb3/sb3_model_file.hpp"

namespace rlrun {

std::string initialize_from_model(const std::string& path, Algorithm& algorithm, VecEnv& env) {
  // An SB3 file holds no env id: it is read as a model of this run's env, whose spaces must
  // then be the file's.
  const bool sb3 = is_sb3_model_file(path);
  ModelFile model = sb3 ? read_sb3_model(path, env.env(0).id()) : read_model_header(path);
  const std::string refused = "cannot initialise from " + path + ": ";
  if (model.meta.algorithm != algorithm.id())
    throw UsageError(refused + "it holds a " + model.meta.algorithm + " model, this run trains " +
                     algorithm.id());
  if (model.meta.observation_space != env.observation_space().describe())
    throw UsageError(refused + "it was trained on observations " + model.meta.observation_space +
                     ", this run's env gives " + env.observation_space().describe());
  if (model.meta.action_space != env.action_space().describe())
    throw UsageError(refused + "it was trained with actions " + model.meta.action_space +
                     ", this run's env takes " + env.action_space().describe());
  // The run's algorithm must take the file's weights, so its size bounds what is read (the
  // statistics: env 0's, which every env shares).
  if (!sb3)
    read_model_tensors(model, ModelParts::kModel, model_tensor_budget(algorithm, env.env(0)));
  try {
    algorithm.load(model.tensors);
  } catch (const std::exception& e) {
    throw UsageError(refused + e.what() + " (other network sizes in algo.policy?)");
  }
  std::string line = "initialised from " + path + " (" + model.meta.algorithm + ", " +
                     model.meta.env_id + ", " + count_of(model.meta.num_timesteps, "step") + ")";
  const bool run_normalises = !model_statistics(env.env(0)).empty();
  if (run_normalises && !model.wrapper_statistics.empty()) {
    try {
      load_model_statistics(env.env(0), model.wrapper_statistics, /*training=*/true);
      line += " with its normalisation statistics";
    } catch (const StateMismatch&) {
      line += "; its normalisation statistics do not fit this run's wrappers: starting them anew";
    }
  } else if (!model.wrapper_statistics.empty()) {
    line +=
        "; note: the model was trained with normalised observations or rewards, this run "
        "has no Normalize wrapper";
  }
  return line;
}

}  // namespace rlrun
