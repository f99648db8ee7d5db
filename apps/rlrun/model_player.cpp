#include "model_player.hpp"

#include <cstdio>
#include <limits>

#include "cli_values.hpp"
#include "rlrun/core/errors.hpp"
#include "rlrun/core/plural.hpp"
#include "rlrun/runtime/io/agent_team_file.hpp"
#include "rlrun/runtime/run/team_actions.hpp"
#include "rlrun/runtime/workflows/zoo/zoo_run_folder.hpp"
#include "trust_option.hpp"

namespace rlrun::cli {

ActionFn ModelPlayer::act(bool deterministic, std::function<void()>* start_episode) {
  if (models.size() == 1)
    return model_action_fn(*models.front().algorithm, env(), deterministic, start_episode);
  std::vector<Algorithm*> algorithms;
  for (LoadedModel& model : models) algorithms.push_back(model.algorithm.get());
  return team_action_fn(algorithms, env(), deterministic, start_episode);
}

YAML::Node resolve_zoo_model(const std::string& dir, const zoo::ZooModelChoice& choice,
                             const Registry& registry, std::string& model, std::string& env_id) {
  if (dir.empty()) return YAML::Node();
  const zoo::ZooRunFolder folder = zoo::find_zoo_run_folder(dir, choice, registry);
  model = folder.model_path;
  if (env_id.empty()) env_id = folder.env_id;
  for (const std::string& note : folder.notes) std::fprintf(stderr, "%s\n", note.c_str());
  return folder.env_section;
}

void add_zoo_model_choice_options(CLI::App* sub, CLI::Option* zoo_option,
                                  zoo::ZooModelChoice& choice) {
  CLI::Option* best = sub->add_flag("--load-best", choice.best,
                                    "--zoo-model: play best_model.zip (the best evaluation's)");
  CLI::Option* checkpoint = sub->add_option("--load-checkpoint", choice.checkpoint,
                                            "--zoo-model: play rl_model_<N>_steps.zip")
                                ->transform(integer_in(1, std::numeric_limits<int64_t>::max()));
  CLI::Option* last = sub->add_flag("--load-last-checkpoint", choice.last_checkpoint,
                                    "--zoo-model: play the checkpoint with the most steps");
  for (CLI::Option* option : {best, checkpoint, last}) option->needs(zoo_option);
  best->excludes(checkpoint)->excludes(last);
  checkpoint->excludes(last);
}

void add_model_env_override(const std::string& env_id, std::vector<std::string>& overrides) {
  if (!env_id.empty()) overrides.insert(overrides.begin(), "env.id=" + env_id);
}

ModelPlayer load_model_player(const std::string& path, Registry& registry,
                              const std::vector<std::string>& overrides, bool trust,
                              const YAML::Node& sb3_env_section) {
  ModelPlayer player;
  const std::optional<std::string> team_dir = agent_team_directory(path);
  if (!team_dir) {
    player.models.push_back(load_model(path, registry, overrides,
                                       model_trust(trust, path, registry), ModelEnv::kRun,
                                       sb3_env_section));
    player.label = player.first().file.meta.algorithm;
    return player;
  }
  const AgentTeamModels team = read_agent_team(*team_dir);
  for (size_t a = 0; a < team.model_paths.size(); ++a) {
    const std::string& model = team.model_paths[a];
    // The first model's env is played; the others only turn into policies.
    player.models.push_back(load_model(model, registry, overrides,
                                       model_trust(trust, model, registry),
                                       a == 0 ? ModelEnv::kRun : ModelEnv::kSpacesOnly));
    const LoadedModel& loaded = player.models.back();
    if (loaded.experiment.env.id != team.team.env_id)
      throw RuntimeFailure(model + " is a model of " + loaded.experiment.env.id + ", not of " +
                           team.team.env_id + " as " + *team_dir + "/" + kAgentTeamFile + " says");
  }
  const int agents = player.env().num_agents();
  if (agents != static_cast<int>(team.model_paths.size()))
    throw RuntimeFailure(*team_dir + "/" + kAgentTeamFile + " lists " +
                         count_of(static_cast<int64_t>(team.model_paths.size()), "agent") +
                         " but " + team.team.env_id + " has " + std::to_string(agents));
  player.label =
      player.first().file.meta.algorithm + ", one per agent (" + count_of(agents, "agent") + ")";
  return player;
}

}  // namespace rlrun::cli
