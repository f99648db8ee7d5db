#include "rlrun/runtime/run/team_actions.hpp"

#include <memory>
#include <stdexcept>
#include <string>

#include "rlrun/env/action_mask.hpp"

namespace rlrun {

namespace {

// What the team's ActionFn keeps between calls.
struct Team {
  std::vector<Algorithm*> models;
  std::vector<ActionFn> unmasked;  // per agent; empty where the model reads the env's masks
  std::vector<std::function<void()>> starts;
  ActionMaskReader masks_of_env;   // every agent's mask, when any model reads them
  Eigen::MatrixXf masks;           // mask size x agents
  Eigen::MatrixXf column, action;  // one agent's observation and action
  bool deterministic = true;
  bool any_masked = false;
  int64_t calls = 0;
};

}  // namespace

ActionFn team_action_fn(const std::vector<Algorithm*>& models, const Env& env, bool deterministic,
                        std::function<void()>* start_episode) {
  const int agents = env.num_agents();
  if (static_cast<int>(models.size()) != agents)
    throw std::invalid_argument(env.id() + " has " + std::to_string(agents) +
                                " agents but the team has " + std::to_string(models.size()) +
                                " models");
  auto team = std::make_shared<Team>(
      Team{models, {}, {}, ActionMaskReader(env.action_space()), {}, {}, {}, deterministic});
  for (Algorithm* model : models) {
    if (model->masks_from_env()) {
      team->unmasked.emplace_back();
      team->any_masked = true;
      continue;
    }
    std::function<void()> start;
    team->unmasked.push_back(model_action_fn(*model, env, deterministic, &start));
    if (start) team->starts.push_back(std::move(start));
  }
  if (start_episode)
    *start_episode = [team] {
      for (const auto& start : team->starts) start();
    };
  return [team, &env](const Eigen::MatrixXf& obs, Eigen::MatrixXf& actions) {
    const int agents = static_cast<int>(obs.cols());
    if (team->any_masked)
      read_env_action_masks(team->masks_of_env, env, agents, team->calls, team->masks);
    ++team->calls;
    for (int a = 0; a < agents; ++a) {
      team->column = obs.col(a);
      if (team->unmasked[a])
        team->unmasked[a](team->column, team->action);
      else
        team->models[a]->predict_masked(team->column, team->masks.col(a), team->deterministic,
                                        team->action);
      if (a == 0) actions.resize(team->action.rows(), agents);
      actions.col(a) = team->action.col(0);
    }
  };
}

}  // namespace rlrun
