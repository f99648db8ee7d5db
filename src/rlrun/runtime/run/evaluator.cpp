#include "rlrun/runtime/run/evaluator.hpp"

#include <cmath>
#include <memory>
#include <stdexcept>
#include <string>

#include "rlrun/core/errors.hpp"
#include "rlrun/env/action_mask.hpp"
#include "rlrun/env/step_all_agents.hpp"

namespace rlrun {

namespace {
double mean_of(const std::vector<double>& v) {
  double s = 0;
  for (double x : v) s += x;
  return v.empty() ? std::nan("") : s / static_cast<double>(v.size());
}
}  // namespace

double EvalResult::mean_return() const { return mean_of(returns); }

double EvalResult::std_return() const {
  const double m = mean_return();
  double s = 0;
  for (double x : returns) s += (x - m) * (x - m);
  return returns.empty() ? std::nan("") : std::sqrt(s / static_cast<double>(returns.size()));
}

double EvalResult::mean_length() const {
  double s = 0;
  for (auto l : lengths) s += static_cast<double>(l);
  return lengths.empty() ? std::nan("") : s / static_cast<double>(lengths.size());
}

namespace {
ActionFn recurrent_action_fn(Algorithm& algorithm, bool deterministic,
                             std::function<void()>* start_episode) {
  if (start_episode == nullptr)
    throw std::logic_error(algorithm.id() + " is recurrent: its episodes need a start hook");
  struct Memory {
    Eigen::MatrixXf states;
    Eigen::RowVectorXf starts;
    bool episode_start = true;
  };
  auto memory = std::make_shared<Memory>();
  *start_episode = [memory] { memory->episode_start = true; };
  return [&algorithm, deterministic, memory](const Eigen::MatrixXf& obs, Eigen::MatrixXf& actions) {
    const Eigen::Index n = obs.cols();
    if (memory->states.cols() != n) memory->states.setZero(algorithm.recurrent_state_size(), n);
    memory->starts.setConstant(n, memory->episode_start ? 1.0f : 0.0f);
    memory->episode_start = false;
    algorithm.predict_recurrent(obs, memory->starts, memory->states, deterministic, actions);
  };
}
}  // namespace

ActionFn model_action_fn(Algorithm& algorithm, const Env& env, bool deterministic,
                         std::function<void()>* start_episode) {
  if (algorithm.recurrent_state_size() > 0)
    return recurrent_action_fn(algorithm, deterministic, start_episode);
  if (!algorithm.masks_from_env())
    return [&algorithm, deterministic](const Eigen::MatrixXf& obs, Eigen::MatrixXf& actions) {
      algorithm.predict(obs, deterministic, actions);
    };
  struct Masks {
    ActionMaskReader reader;
    Eigen::MatrixXf values;
    int64_t calls = 0;
  };
  auto masks = std::make_shared<Masks>(Masks{ActionMaskReader(env.action_space()), {}, 0});
  return [&algorithm, &env, deterministic, masks](const Eigen::MatrixXf& obs,
                                                  Eigen::MatrixXf& actions) {
    read_env_action_masks(masks->reader, env, static_cast<int>(obs.cols()), masks->calls++,
                          masks->values);
    algorithm.predict_masked(obs, masks->values, deterministic, actions);
  };
}

void read_env_action_masks(ActionMaskReader& reader, const Env& env, int agents, int64_t step,
                           Eigen::MatrixXf& masks) {
  masks.resize(reader.size(), agents);
  const std::string problem =
      reader.read(env.info(), agents, {masks.data(), static_cast<size_t>(masks.size())});
  if (!problem.empty())
    throw RuntimeFailure(env.id() + " at step " + std::to_string(step) +
                         " of the episodes: " + problem);
}

EvalResult evaluate_policy(Algorithm& algorithm, Env& env, int n_episodes, bool deterministic,
                           std::optional<uint64_t> seed) {
  std::function<void()> start_episode;
  const ActionFn act = model_action_fn(algorithm, env, deterministic, &start_episode);
  return evaluate_policy(act, env, n_episodes, seed, start_episode);
}

EvalResult evaluate_policy(const ActionFn& policy, Env& env, int n_episodes,
                           std::optional<uint64_t> seed,
                           const std::function<void()>& start_episode) {
  EvalResult result;
  const int obs_dim = env.observation_space().flat_dim();
  // Several agents (include/rlrun/env.hpp): one column each, stepped together; the episode's
  // return is the sum of all agents' rewards, as Monitor counts it.
  const int agents = env.num_agents();
  const size_t obs_size = static_cast<size_t>(obs_dim) * agents;
  Eigen::MatrixXf obs(obs_dim, agents);
  Eigen::MatrixXf actions;
  std::vector<StepResult> steps;
  const int r_key = env.info().find("episode.r");
  const int l_key = env.info().find("episode.l");
  const int success_key = env.info().find("is_success");
  std::vector<int> metric_indices;
  const std::vector<std::string>& keys = env.unwrapped().info().keys();
  for (const std::string& key : keys) {
    // Not metrics: Monitor's and TimeLimit's keys, and the action mask (env/action_mask.hpp).
    if (key == "is_success" || key.rfind("episode.", 0) == 0 || key == "TimeLimit.truncated" ||
        key.rfind("action_mask.", 0) == 0)
      continue;
    const int index = env.info().find(key);
    if (index < 0) continue;
    result.metric_keys.push_back(key);
    metric_indices.push_back(index);
  }
  for (int episode = 0; episode < n_episodes; ++episode) {
    env.reset(episode == 0 ? seed : std::nullopt, {obs.data(), obs_size});
    if (start_episode) start_episode();
    double episode_return = 0;
    int64_t length = 0;
    while (true) {
      policy(obs, actions);
      const StepResult step =
          step_all_agents(env, {actions.data(), static_cast<size_t>(actions.size())},
                          {obs.data(), obs_size}, steps);
      episode_return += step.reward;
      const bool done = step.terminated || step.truncated;
      ++length;
      if (done) {
        const Info& info = env.info();
        result.returns.push_back(info.has(r_key) ? info.get(r_key) : episode_return);
        result.lengths.push_back(info.has(l_key) ? static_cast<int64_t>(info.get(l_key)) : length);
        if (info.has(success_key)) result.successes.push_back(info.get(success_key));
        std::vector<double> values;
        for (const int index : metric_indices) values.push_back(info.get(index));
        result.metrics.push_back(std::move(values));
        break;
      }
    }
  }
  return result;
}

}  // namespace rlrun
