// rlrun check-env ID|CONFIG [--plugin LIB]... [--set key=value]... [--seed N] [--steps N]
//                 [--episodes N]
// SB3's check_env for rlrun envs (stable_baselines3/common/env_checker.py; the checks are
// rlrun's env/env_checker.hpp): builds the env as `rlrun train` would, prints its spaces,
// time limit, info keys and parameters, runs the conformance checks, and plays a few
// random-policy episodes as a baseline. The first thing to run on a new (plugin) env.
// Exit code 0 when the env passes, 1 when it has problems, 2 for a bad id or parameter.
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "cli_values.hpp"
#include "commands.hpp"
#include "plugin_option.hpp"
#include "rlrun/core/config_fields.hpp"
#include "rlrun/core/errors.hpp"
#include "rlrun/core/plural.hpp"
#include "rlrun/env/env_checker.hpp"
#include "rlrun/env/random_actions.hpp"
#include "rlrun/env/space_text.hpp"
#include "rlrun/env/step_all_agents.hpp"
#include "rlrun/rng.hpp"
#include "rlrun/runtime/components/builtins.hpp"
#include "rlrun/runtime/experiment/env_factory.hpp"
#include "rlrun/runtime/experiment/experiment.hpp"
#include "rlrun/wrappers/time_limit.hpp"

namespace rlrun::cli {

namespace {

struct CheckTarget {
  EnvPtr env;
  std::string description;  // registry line
  std::string params;       // resolved kwargs, "k=v, ..."
  int time_limit = 0;
};

std::string flow(const YAML::Node& node) {
  std::string text;
  if (!node.IsMap()) return text;
  for (const auto& kv : node) {
    YAML::Emitter out;
    out.SetMapFormat(YAML::Flow);
    out.SetSeqFormat(YAML::Flow);
    out << kv.second;
    text += (text.empty() ? "" : ", ") + kv.first.as<std::string>() + "=" + out.c_str();
  }
  return text.empty() ? "(none)" : text;
}

bool is_config_file(const std::string& arg) {
  const std::string ext = std::filesystem::path(arg).extension().string();
  return (ext == ".yaml" || ext == ".yml") && std::filesystem::is_regular_file(arg);
}

// An id: the registered env with `--set` kwargs and its TimeLimit, as gymnasium.make builds it.
CheckTarget target_from_id(const std::string& id, const std::vector<std::string>& overrides,
                           const Registry& registry, const EnvContext& context) {
  // Path "" so that errors name the key as typed after --set.
  ConfigNode kwargs = ConfigNode::from_yaml(YAML::Node(YAML::NodeType::Map), "command line");
  for (const auto& o : overrides) kwargs.apply_override(o);
  const ConfigNode id_node = ConfigNode::from_yaml(YAML::Node(id), "command line", "ID");
  const EnvEntry& entry = registry.env(id, id_node);
  CheckTarget t;
  t.description = entry.description;
  const AnyConfig config = entry.parse(kwargs);
  t.params = flow(config.resolved());
  try {
    t.env = entry.build(config, context);
  } catch (const std::invalid_argument& e) {
    const std::string what = e.what();
    throw UsageError(what.rfind(id, 0) == 0 ? what : id + ": " + what);
  }
  t.time_limit = entry.max_episode_steps;
  if (t.time_limit > 0) t.env = std::make_unique<TimeLimit>(std::move(t.env), t.time_limit);
  return t;
}

// A config file: its env section as training builds it (env_factory.cpp make_env: time
// limit, wrappers, action-space adapter) but without the Monitor, whose info reports wall
// time and so would fail the determinism check.
CheckTarget target_from_config(const std::string& path, const std::vector<std::string>& overrides,
                               Registry& registry) {
  const Experiment exp = load_experiment(path, overrides, registry);
  CheckTarget t;
  const EnvEntry& entry = *registry.find_env(exp.env.id);
  t.description = entry.description;
  t.params = flow(exp.resolved["env"]["kwargs"]);
  t.time_limit = exp.env.section.max_episode_steps.value_or(entry.max_episode_steps);
  t.env = entry.build(exp.env.kwargs, env_context(exp.env.section));
  if (t.time_limit > 0) t.env = std::make_unique<TimeLimit>(std::move(t.env), t.time_limit);
  for (const WrapperSpec& w : exp.env.wrappers)
    t.env = registry.find_wrapper(w.id)->make(std::move(t.env), w.params);
  t.env = adapt_action_space(std::move(t.env), exp.env, registry);
  return t;
}

struct RandomBaseline {
  double mean_return = 0, std_return = 0, mean_length = 0;
  int successes = 0, with_success = 0;
};

RandomBaseline play_random(Env& env, int episodes, uint64_t seed) {
  Rng rng(seed + 12345);
  // A multi-agent env: every agent acts at random; the return sums all agents' rewards.
  const int agents = env.num_agents();
  const size_t act_dim = static_cast<size_t>(env.action_space().flat_dim());
  std::vector<float> obs(static_cast<size_t>(env.observation_space().flat_dim()) * agents);
  std::vector<float> action(act_dim * agents);
  std::vector<StepResult> results;
  RandomActions random_actions(env.action_space());  // legal ones when the env masks them
  std::vector<double> returns;
  double total_length = 0;
  RandomBaseline b;
  const int success_key = env.info().find("is_success");
  for (int e = 0; e < episodes; ++e) {
    env.reset(e == 0 ? std::optional<uint64_t>(seed) : std::nullopt, obs);
    double ret = 0;
    for (int64_t t = 1;; ++t) {
      random_actions.sample(env.info(), agents, rng, action);
      const StepResult r = step_all_agents(env, action, obs, results);
      ret += r.reward;
      if (r.terminated || r.truncated || t >= 100000) {
        total_length += static_cast<double>(t);
        if (env.info().has(success_key)) {
          ++b.with_success;
          b.successes += env.info().get(success_key) > 0.5 ? 1 : 0;
        }
        break;
      }
    }
    returns.push_back(ret);
  }
  for (double r : returns) b.mean_return += r / episodes;
  for (double r : returns) b.std_return += (r - b.mean_return) * (r - b.mean_return) / episodes;
  b.std_return = std::sqrt(b.std_return);
  b.mean_length = total_length / episodes;
  return b;
}

}  // namespace

Action add_check_env(CLI::App& app, Registry& registry) {
  struct Options {
    std::string target;
    std::vector<std::string> plugins;
    std::vector<std::string> overrides;
    uint64_t seed = 0;
    int steps = 1000;
    int episodes = 20;
    std::string python;
  };
  auto options = std::make_shared<Options>();
  CLI::App* sub = app.add_subcommand(
      "check-env", "check that an environment follows the Env contract (SB3's check_env)");
  sub->add_option("env", options->target, "an env id (e.g. Grasp2D-v0) or an experiment file")
      ->required();
  add_plugin_option(sub, options->plugins);
  sub->add_option("--set", options->overrides,
                  "with an id: an env parameter, e.g. --set step_size=0.1; with a file: any "
                  "config value, e.g. --set env.kwargs.step_size=0.1 (repeatable)")
      ->allow_extra_args(false);
  sub->add_option(
      "--python", options->python,
      "interpreter of a python:/gymnasium:/pettingzoo: id (default: python3 on PATH; for a "
      "file: its env.python)");
  sub->add_option("--seed", options->seed, "seed of the checks and the random episodes")
      ->check(seed_value());
  sub->add_option("--steps", options->steps, "random steps per determinism rollout")
      ->transform(integer_in(1));
  sub->add_option("--episodes", options->episodes, "random-policy episodes for the baseline")
      ->transform(integer_in(0));
  return [options, &registry]() {
    load_plugin_options(options->plugins, registry);
    CheckTarget t =
        is_config_file(options->target)
            ? target_from_config(options->target, options->overrides, registry)
            : target_from_id(options->target, options->overrides, registry,
                             options->python.empty() ? EnvContext{} : EnvContext{options->python});
    Env& env = *t.env;
    std::string keys;
    for (const auto& k : env.info().keys()) keys += (keys.empty() ? "" : ", ") + k;
    std::printf("%s: %s\n", env.id().c_str(), t.description.c_str());
    std::printf("%s", labeled_space("observation_space", env.observation_space(), 17).c_str());
    std::printf("%s", labeled_space("action_space", env.action_space(), 17).c_str());
    if (env.num_agents() > 1)
      std::printf("  agents             %d (the spaces are each agent's; one shared policy)\n",
                  env.num_agents());
    std::printf("  time limit         %s\n",
                t.time_limit > 0 ? (count_of(t.time_limit, "step") + " (TimeLimit)").c_str()
                                 : "none (the env ends its own episodes)");
    std::printf("  info keys          %s\n", keys.empty() ? "(none)" : keys.c_str());
    std::printf("  parameters         %s\n", t.params.c_str());

    const std::vector<std::string> problems = check_env(env, options->seed, options->steps);
    if (!problems.empty()) {
      std::printf("check_env: %s\n",
                  count_of(static_cast<int64_t>(problems.size()), "problem").c_str());
      for (const auto& p : problems) std::printf("  - %s\n", p.c_str());
      return kExitRuntime;
    }
    std::printf(
        "check_env: passed (seeding, spaces, determinism, finite rewards; seed %llu, "
        "2 x %d random steps)\n",
        static_cast<unsigned long long>(options->seed), options->steps);
    if (options->episodes > 0) {
      const RandomBaseline b = play_random(env, options->episodes, options->seed);
      std::printf("random policy, %s: return %.2f +/- %.2f, length %.1f",
                  count_of(options->episodes, "episode").c_str(), b.mean_return, b.std_return,
                  b.mean_length);
      if (b.with_success > 0)
        std::printf(", success rate %.2f", static_cast<double>(b.successes) / b.with_success);
      std::printf("\n");
    }
    return kExitOk;
  };
}

}  // namespace rlrun::cli
