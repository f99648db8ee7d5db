#include "rlrun/runtime/io/model_file.hpp"

#include <nlohmann/json.hpp>

#include "rlrun/core/errors.hpp"
#include "rlrun/core/npy.hpp"
#include "rlrun/core/zip_archive.hpp"
#include "rlrun/env/space_json.hpp"

namespace rlrun {

void save_model(const std::string& path, const Algorithm& algorithm, const Experiment& experiment,
                Env& env, const TensorMap& env_tensors) {
  write_zip_atomic(path, model_members(algorithm, experiment, env, env_tensors));
}

ZipMembers model_members(const Algorithm& algorithm, const Experiment& experiment, Env& env,
                         const TensorMap& env_tensors) {
  TensorMap tensors;
  algorithm.save(tensors);
  ZipMembers members;
  for (const auto& [name, tensor] : tensors) members[name + ".npy"] = encode_npy(tensor);
  for (const auto& [name, tensor] : env_tensors) members[name + ".npy"] = encode_npy(tensor);
  const std::string config = dump_yaml(experiment.resolved);
  members["config.yaml"] = std::vector<uint8_t>(config.begin(), config.end());
  const Env& own = env.unwrapped();
  nlohmann::ordered_json meta;
  meta["format_version"] = kModelFormatVersion;
  meta["rlrun_version"] = RLRUN_VERSION;
  meta["algorithm"] = algorithm.id();
  meta["env_id"] = experiment.env.id;
  meta["observation_space"] = env.observation_space().describe();
  meta["action_space"] = env.action_space().describe();
  meta["num_timesteps"] = algorithm.num_timesteps();
  meta["env_spaces"] = {{"observation_space", space_to_json(own.observation_space())},
                        {"action_space", space_to_json(own.action_space())},
                        {"num_agents", own.num_agents()}};
  if (const RenderSpec render = own.render_spec(); render.width > 0 && render.height > 0)
    meta["env_spaces"]["render"] = {
        {"width", render.width}, {"height", render.height}, {"fps", render.fps}};
  const std::string meta_text = meta.dump(2) + "\n";
  members["meta.json"] = std::vector<uint8_t>(meta_text.begin(), meta_text.end());
  return members;
}

}  // namespace rlrun
