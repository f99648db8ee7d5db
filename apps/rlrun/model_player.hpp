#pragma once
// What `rlrun eval --model` and `rlrun record --model` play: one model file, or the run
// directory of a per-agent run (runtime/run/per_agent_training.hpp; its agents.json, or the
// directory holding it), whose agents each act through their own model.
#include <CLI/CLI.hpp>
#include <functional>
#include <string>
#include <vector>

#include "rlrun/runtime/components/registry.hpp"
#include "rlrun/runtime/io/model_loader.hpp"
#include "rlrun/runtime/run/evaluator.hpp"
#include "rlrun/runtime/workflows/zoo/zoo_run_folder.hpp"

namespace rlrun::cli {

struct ModelPlayer {
  // The models; the first one's env is the env played (a team's: the whole multi-agent env).
  std::vector<LoadedModel> models;
  std::string label;  // "PPO", or "PPO, one per agent (3 agents)"

  Env& env() { return *models.front().env; }
  const LoadedModel& first() const { return models.front(); }
  // The joint action; `start_episode` as model_action_fn's.
  ActionFn act(bool deterministic, std::function<void()>* start_episode);
};

// `--env ID` with `--model`: the env the model plays, as the override env.id=ID before the
// user's --set values (an SB3 model file does not record its env; an rlrun one is played on
// another env with the same spaces). Nothing when `env_id` is empty.
void add_model_env_override(const std::string& env_id, std::vector<std::string>& overrides);

// `--zoo-model DIR` (an rl-zoo run folder: runtime/workflows/zoo/zoo_run_folder.hpp): sets
// `model` to its model file and `env_id` to its env unless the user named one, and prints
// what of the zoo's config.yml is not applied. Returns the folder's env settings for
// load_model_player (nothing when `dir` is empty).
YAML::Node resolve_zoo_model(const std::string& dir, const zoo::ZooModelChoice& choice,
                             const Registry& registry, std::string& model, std::string& env_id);
// rl_zoo3.enjoy's --load-best, --load-checkpoint N, --load-last-checkpoint, for --zoo-model.
void add_zoo_model_choice_options(CLI::App* sub, CLI::Option* zoo_option,
                                  zoo::ZooModelChoice& choice);

// Loads `path` (a model file, a per-agent run directory or its agents.json) as `eval` and
// `record` do: statistics frozen, weights within the budget, `overrides` and `trust` applied to
// every model file. A team's models must agree on the env and the agents' number.
// `sb3_env_section`: resolve_zoo_model's env settings for an SB3 model file.
ModelPlayer load_model_player(const std::string& path, Registry& registry,
                              const std::vector<std::string>& overrides, bool trust,
                              const YAML::Node& sb3_env_section = YAML::Node());

}  // namespace rlrun::cli
