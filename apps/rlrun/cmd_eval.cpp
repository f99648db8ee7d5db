// rlrun eval --model FILE [--episodes N] [--seed S] [--deterministic|--stochastic] [--csv FILE]
//            [--record video.mp4] [--baseline fixed-time [--green-time S] | --baseline scripted]
//            [--trajectory steps.csv]
// rlrun eval --env ID | --config CFG  --policy scripted|fixed-time|random[,...]  [--episodes N] ...
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <optional>
#include <sstream>

#include "cli_values.hpp"
#include "commands.hpp"
#include "env_by_id.hpp"
#include "game_opponent_option.hpp"
#include "model_player.hpp"
#include "named_policy.hpp"
#include "plugin_option.hpp"
#include "policy_comparison.hpp"
#include "rlrun/core/checked_file.hpp"
#include "rlrun/core/errors.hpp"
#include "rlrun/core/plural.hpp"
#include "rlrun/runtime/components/builtins.hpp"
#include "rlrun/runtime/experiment/env_factory.hpp"
#include "rlrun/runtime/experiment/experiment.hpp"
#include "rlrun/runtime/io/log_sinks.hpp"
#include "rlrun/runtime/io/model_loader.hpp"
#include "rlrun/runtime/run/evaluator.hpp"
#include "rlrun/runtime/run/recorder.hpp"
#include "rlrun/runtime/run/trajectory_tap.hpp"
#include "trust_option.hpp"

namespace rlrun::cli {

namespace {

// "<what> on <env>, N episodes<how>: mean_reward = m +/- s, mean_ep_length = l", the line
// scripts and users grep for, then the success rate and the env's own metrics.
void print_summary(const std::string& what, const std::string& how, const std::string& env_id,
                   int episodes, const EvalResult& r) {
  std::printf("%s on %s, %s%s: mean_reward = %.2f +/- %.2f, mean_ep_length = %.1f\n", what.c_str(),
              env_id.c_str(), count_of(episodes, "episode").c_str(), how.c_str(), r.mean_return(),
              r.std_return(), r.mean_length());
  if (!r.successes.empty()) {
    double s = 0;
    for (double x : r.successes) s += x;
    std::printf("success_rate = %.3f\n", s / static_cast<double>(r.successes.size()));
  }
  // An episode whose last info lacks a key (NaN; e.g. CarRacing's lap_finished, set only when
  // an episode ends by itself, not at the time limit) does not count for that key's mean.
  for (size_t k = 0; k < r.metric_keys.size(); ++k) {
    double sum = 0;
    size_t present = 0;
    for (const auto& episode : r.metrics)
      if (!std::isnan(episode[k])) sum += episode[k], ++present;
    if (present == 0) continue;
    if (present == r.metrics.size())
      std::printf("  %s = %.3f (mean over episodes)\n", r.metric_keys[k].c_str(),
                  sum / static_cast<double>(present));
    else
      std::printf("  %s = %.3f (mean over the %zu of %zu episodes that report it)\n",
                  r.metric_keys[k].c_str(), sum / static_cast<double>(present), present,
                  r.metrics.size());
  }
}

// The --csv layout, one tidy table for every use (pandas reads each column with one type):
//   policy,episode,return,length[,is_success][,<the env's metric columns>]
// one row per episode of each policy (the model's algorithm, e.g. "PPO", then the baseline's
// name), episodes numbered from 0; no summary rows (print_summary shows the means).
// is_success appears when the env reports it, the metrics when the env has any (the traffic
// task's avg_waiting_time, ...); every policy of one file ran on the same env, so they share
// the columns.
void write_csv(const std::string& path,
               const std::vector<std::pair<std::string, EvalResult>>& runs) {
  const std::filesystem::path parent = std::filesystem::path(path).parent_path();
  std::error_code ec;
  if (!parent.empty()) std::filesystem::create_directories(parent, ec);  // e.g. results/
  std::ostringstream csv;  // written at the end, every write checked (a full disk: exit 1)
  const EvalResult& first = runs.front().second;
  const bool with_success = std::any_of(
      runs.begin(), runs.end(), [](const auto& run) { return !run.second.successes.empty(); });
  csv << "policy,episode,return,length" << (with_success ? ",is_success" : "");
  for (const auto& key : first.metric_keys) csv << ',' << key;
  csv << '\n';
  for (const auto& [policy, r] : runs) {
    for (size_t i = 0; i < r.returns.size(); ++i) {
      csv << policy << ',' << i << ',' << r.returns[i] << ',' << r.lengths[i];
      if (with_success) csv << ',' << (i < r.successes.size() ? r.successes[i] : 0.0);
      for (size_t k = 0; k < first.metric_keys.size(); ++k)
        csv << ',' << (i < r.metrics.size() && k < r.metrics[i].size() ? r.metrics[i][k] : NAN);
      csv << '\n';
    }
  }
  // Written in place, not renamed over: --csv may name /dev/stdout or a pipe.
  CheckedFile file(path, CheckedFile::Mode::kTruncate);
  file << csv.str();
  file.close();
}

// The files written after the episodes (--csv, --trajectory) can be written: a bad path fails
// before the first episode, not after the last.
template <class Options>
void check_outputs(const Options& o) {
  if (!o.csv.empty()) check_writable_file(o.csv);
  if (!o.trajectory.empty()) check_writable_file(o.trajectory);
}

// The command line's settings for a named policy (--green-time for the traffic baseline).
template <class Options>
PolicyOptions policy_options(const Options& o) {
  PolicyOptions options;
  options.seed = o.seed;
  if (o.green_time) options.settings["green_time"] = *o.green_time;
  return options;
}

// "" or " (green_time 30)": the settings a baseline ran with.
std::string settings_text(const PolicyOptions& options) {
  std::string text;
  for (const auto& [key, value] : options.settings)
    text += (text.empty() ? " (" : ", ") + key + " " + format_log_value(value);
  return text.empty() ? text : text + ")";
}

// The env `eval --policy` runs in: --env ID's, or --config CFG's env.
template <class Options>
EnvPtr policy_env(const Options& o, Registry& registry) {
  EnvPtr env = o.env_id.empty() ? make_env(load_experiment(o.config, o.overrides, registry).env,
                                           registry, "", unix_time_now())
                                : env_by_id(o.env_id, registry, o.overrides);
  give_opponent_model(o.game, *env, registry);
  return env;
}

// "a,b,c" -> {a, b, c}: --policy's names.
std::vector<std::string> policy_names(const std::string& list) {
  std::vector<std::string> names;
  std::stringstream in(list);
  for (std::string name; std::getline(in, name, ',');) {
    if (name.empty()) throw UsageError("--policy " + list + ": an empty policy name");
    names.push_back(name);
  }
  if (list.empty() || list.back() == ',')
    throw UsageError("--policy " + list + ": an empty policy name");
  return names;
}

// `eval --policy a,b,c`: each policy on an env of its own (a baseline may take over the env,
// as fixed-time hands the lights to SUMO), each env's first reset seeded with --seed, so every
// policy plays the same episodes as `--model M --baseline P` does; one row per policy. Every
// policy is built before any episode runs, so a wrong name costs nothing.
template <class Options>
int compare_policies(const Options& o, Registry& registry, const std::vector<std::string>& names) {
  if (!o.trajectory.empty())
    throw UsageError("--trajectory writes one policy's steps: give --policy one name");
  check_outputs(o);
  std::vector<std::pair<EnvPtr, NamedPolicy>> players;
  for (const std::string& name : names) {
    EnvPtr env = policy_env(o, registry);
    NamedPolicy policy = named_policy(name, *env, registry, policy_options(o));
    players.emplace_back(std::move(env), std::move(policy));
  }
  std::vector<std::pair<std::string, EvalResult>> runs;
  for (size_t i = 0; i < names.size(); ++i)
    runs.emplace_back(
        names[i], evaluate_policy(players[i].second.act, *players[i].first, o.episodes, o.seed));
  std::printf("%s on %s, %s each from seed %llu (the same episodes for every policy)%s:\n%s",
              o.policy.c_str(), players.front().first->id().c_str(),
              count_of(o.episodes, "episode").c_str(), static_cast<unsigned long long>(o.seed),
              settings_text(policy_options(o)).c_str(), comparison_table(runs).c_str());
  if (!o.csv.empty()) write_csv(o.csv, runs);
  return 0;
}

// `eval --policy P --env ID | --config CFG`: a policy that needs no model file, e.g. the grasp
// task's scripted controller (shows the task is solvable) or a uniform random policy; several
// (`--policy a,b,c`) are compared in one table.
template <class Options>
int evaluate_without_model(const Options& o, Registry& registry) {
  if (o.env_id.empty() == o.config.empty())
    throw UsageError("--policy " + o.policy + " needs exactly one of --env ID or --config CFG");
  if (!o.baseline.empty())
    throw UsageError("--baseline compares with a model: use it with --model");
  const std::vector<std::string> names = policy_names(o.policy);
  if (names.size() > 1) return compare_policies(o, registry, names);
  check_outputs(o);
  EnvPtr env = policy_env(o, registry);
  const TrajectoryTap* tap = o.trajectory.empty() ? nullptr : &tap_trajectory(*env);
  const EvalResult r = evaluate_policy(
      named_policy(o.policy, *env, registry, policy_options(o)).act, *env, o.episodes, o.seed);
  print_summary(o.policy, "", env->id(), o.episodes, r);
  if (!o.csv.empty()) write_csv(o.csv, {{o.policy, r}});
  if (tap) write_trajectory(*tap, o.trajectory);
  return 0;
}

// `rlrun eval`'s options.
struct EvalOptions {
  bool deterministic = false;  // --deterministic: the default, stated
  std::string model;
  int episodes = 10;
  uint64_t seed = 0;
  bool stochastic = false;
  std::string csv;
  std::string record;  // mp4 of the evaluation episodes
  std::vector<std::string> plugins;
  std::string baseline;                // fixed-time (traffic task) or scripted (grasp task)
  std::optional<int> green_time;       // --green-time (the traffic task's fixed-time plan)
  std::string policy, env_id, config;  // a policy without a model, in an env or config's env
  std::string zoo_model;               // --zoo-model DIR: an rl-zoo run folder
  zoo::ZooModelChoice zoo_choice;      // --load-best, --load-checkpoint N, --load-last-checkpoint
  YAML::Node zoo_env;                  // its env settings (resolve_zoo_model)
  std::vector<std::string> overrides;  // --set: the user's values over the model's config
  std::string
      trajectory;      // every step's env observation and action (runtime/run/trajectory_tap.hpp)
  bool trust = false;  // --trust: run what the model file names (trust_option.hpp)
  GameOpponentOptions game;  // --opponent, --side (two-player games)
};

// The model's episodes: evaluate_policy's, or the same episodes filmed (record_episodes).
EvalResult run_model_episodes(const EvalOptions& o, ModelPlayer& player) {
  Env& env = player.env();
  const bool deterministic = !o.stochastic;
  std::function<void()> start_episode;
  const ActionFn act = player.act(deterministic, &start_episode);
  if (o.record.empty()) return evaluate_policy(act, env, o.episodes, o.seed, start_episode);
  RecordOptions record;
  record.video_path = o.record;
  record.episodes = o.episodes;
  record.seed = o.seed;
  record.policy_label = player.label + (o.stochastic ? " stochastic" : " deterministic");
  const RecordResult recorded = record_episodes(env, act, record, start_episode);
  std::printf("recorded %s at %dx%d -> %s\n", count_of(recorded.frames, "frame").c_str(),
              recorded.width, recorded.height, o.record.c_str());
  return recorded.episodes;
}

int evaluate_model(const EvalOptions& o, Registry& registry) {
  check_outputs(o);
  // Normalisation statistics frozen; tensors read within the config's budget. A per-agent
  // run's directory plays each agent through its own model.
  ModelPlayer player = load_model_player(o.model, registry, o.overrides, o.trust, o.zoo_env);
  const ModelFile& model = player.first().file;
  give_opponent_model(o.game, player.env(), registry);
  const TrajectoryTap* tap = o.trajectory.empty() ? nullptr : &tap_trajectory(player.env());
  const Experiment& experiment = player.first().experiment;
  // The baseline runs the same episodes on an env of its own; it is built (and checked to
  // fit the env) before anything is evaluated.
  EnvPtr baseline_env;
  std::optional<NamedPolicy> baseline_policy;
  if (!o.baseline.empty()) {
    baseline_env = make_model_env(model, experiment, registry);
    give_opponent_model(o.game, *baseline_env, registry);
    baseline_policy = named_policy(o.baseline, *baseline_env, registry, policy_options(o));
  }
  const EvalResult r = run_model_episodes(o, player);
  std::vector<std::pair<std::string, EvalResult>> runs{{model.meta.algorithm, r}};
  print_summary(player.label, o.stochastic ? " (stochastic)" : " (deterministic)",
                experiment.env.id, o.episodes, r);
  if (baseline_policy) {
    const EvalResult baseline =
        evaluate_policy(baseline_policy->act, *baseline_env, o.episodes, o.seed);
    print_summary(o.baseline, settings_text(policy_options(o)), experiment.env.id, o.episodes,
                  baseline);
    runs.emplace_back(o.baseline, baseline);
  }
  if (!o.csv.empty()) write_csv(o.csv, runs);
  if (tap) write_trajectory(*tap, o.trajectory);
  return 0;
}

}  // namespace

Action add_eval(CLI::App& app, Registry& registry) {
  auto options = std::make_shared<EvalOptions>();
  CLI::App* sub =
      app.add_subcommand("eval", "evaluate a trained model (needs only the model file)");
  CLI::Option* model_option =
      sub->add_option("--model", options->model,
                      "model.zip written by rlrun train, or a per-agent run's directory (its "
                      "agents.json): every agent plays its own model");
  CLI::Option* policy_option = sub->add_option(
      "--policy", options->policy,
      "evaluate a policy without a model: random, or one that comes with the env (`rlrun list "
      "ID` shows them: fixed-time for the traffic task, scripted for the grasp task); several "
      "separated by commas (a,b,c) are compared on the same episodes in one table; needs "
      "--env ID or --config CFG");
  policy_option->excludes(model_option);
  CLI::Option* zoo_option = sub->add_option(
      "--zoo-model", options->zoo_model,
      "an rl-baselines3-zoo run folder (<algo>/<env>_<n>/, as rl-trained-agents has them): its "
      "<env>.zip on its env, VecNormalize statistics frozen, as rl_zoo3.enjoy plays it");
  zoo_option->excludes(model_option)->excludes(policy_option);
  add_zoo_model_choice_options(sub, zoo_option, options->zoo_choice);
  sub->add_option("--env", options->env_id,
                  "env id for --policy; with --model, the env to play (needed for an SB3 model "
                  "file, which does not record it: docs/sb3_models.md)");
  sub->add_option("--config", options->config, "experiment file whose env --policy runs in")
      ->needs(policy_option);
  sub->add_option("--episodes", options->episodes, "number of episodes")->transform(integer_in(1));
  sub->add_option("--seed", options->seed, "seed of the first episode's reset")
      ->check(seed_value());
  CLI::Option* det = sub->add_flag("--deterministic", options->deterministic,
                                   "use the deterministic policy (default)");
  sub->add_flag("--stochastic", options->stochastic, "sample actions from the policy")
      ->excludes(det);
  sub->add_option("--csv", options->csv,
                  "also write one row per episode of each policy: policy,episode,return,length, "
                  "then is_success and the env's metrics where it has them (the means are "
                  "printed, not written)");
  add_plugin_option(sub, options->plugins);
  add_trust_option(sub, options->trust)->needs(model_option);
  sub->add_option("--set", options->overrides,
                  "override a value of the model's config or --config (a model file is "
                  "untrusted: this is how you vouch for a program or file it names; repeatable)")
      ->allow_extra_args(false);
  sub->add_option("--baseline", options->baseline,
                  "also evaluate a baseline on the same episodes: random, or one that comes with "
                  "the env (fixed-time: the traffic task's N -> S -> E -> W plan; scripted: the "
                  "grasp task's controller)");
  sub->add_option("--green-time", options->green_time,
                  "green seconds per approach of the fixed-time baseline")
      ->transform(integer_in(1));
  sub->add_option("--record", options->record,
                  "also record the episodes to this mp4 (same episodes and numbers; needs ffmpeg)");
  sub->add_option("--trajectory", options->trajectory,
                  "also write every step's env observation and action (as the env itself sees "
                  "them, below the model's wrappers) to this CSV, floats with 9 significant "
                  "digits (exact float32)");
  add_game_opponent_options(sub, options->game);
  return [options, &registry]() {
    load_plugin_options(options->plugins, registry);  // model files name theirs: not loaded
    add_game_opponent_overrides(options->game, options->overrides);
    if (!options->policy.empty()) return evaluate_without_model(*options, registry);
    options->zoo_env = resolve_zoo_model(options->zoo_model, options->zoo_choice, registry,
                                         options->model, options->env_id);
    add_model_env_override(options->env_id, options->overrides);
    if (options->model.empty())
      throw UsageError("eval needs --model FILE, or --policy P with --env ID");
    return evaluate_model(*options, registry);
  };
}

}  // namespace rlrun::cli
