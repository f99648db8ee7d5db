// rlrun record: video (mp4) and/or PNG frames of a policy acting in its env.
//   rlrun record --model FILE --output video.mp4 [--episodes N] [--fps F] [--size WxH]
//                [--deterministic|--stochastic] [--seed S] [--frames DIR] [--no-overlay]
//   rlrun record --config CFG --policy random ...     (no model; the config's env)
//   rlrun record --env ID --policy random ...         (no model, no config)
//   rlrun record --from-obs DIR_OR_NPY --env ID --output video.mp4   (an observation log)
#include <cstdio>
#include <iostream>
#include <memory>
#include <regex>

#include "cli_values.hpp"
#include "commands.hpp"
#include "env_by_id.hpp"
#include "game_opponent_option.hpp"
#include "model_player.hpp"
#include "named_policy.hpp"
#include "plugin_option.hpp"
#include "rlrun/core/errors.hpp"
#include "rlrun/core/interrupt.hpp"
#include "rlrun/core/plural.hpp"
#include "rlrun/render/video_limits.hpp"
#include "rlrun/runtime/components/builtins.hpp"
#include "rlrun/runtime/experiment/env_factory.hpp"
#include "rlrun/runtime/io/model_loader.hpp"
#include "rlrun/runtime/io/observation_log.hpp"
#include "rlrun/runtime/run/evaluator.hpp"
#include "rlrun/runtime/run/recorder.hpp"
#include "trust_option.hpp"

namespace rlrun::cli {

namespace {

struct Options {
  std::string model, config, env_id, from_obs, policy;
  std::string zoo_model;           // --zoo-model DIR: an rl-zoo run folder
  zoo::ZooModelChoice zoo_choice;  // --load-best, --load-checkpoint N, --load-last-checkpoint
  YAML::Node zoo_env;              // its env settings (resolve_zoo_model)
  std::optional<int> green_time;   // --green-time (the traffic task's fixed-time plan)
  std::vector<std::string> overrides;
  std::vector<std::string> plugins;
  std::string output, frames, size;
  int episodes = 1;
  uint64_t seed = 0;
  std::optional<double> fps;
  bool stochastic = false;
  bool no_overlay = false;
  bool trust = false;        // --trust: run what the model file names (trust_option.hpp)
  GameOpponentOptions game;  // --opponent, --side (two-player games)
};

// "600x400" -> width, height, bounded up front (render/video_limits.hpp): a size ffmpeg would
// refuse must not first cost the memory of its frames.
void parse_size(const std::string& text, RecordOptions& record, bool video) {
  static const std::regex pattern(R"((\d{1,5})[xX](\d{1,5}))");
  std::smatch m;
  if (!std::regex_match(text, m, pattern))
    throw UsageError("--size " + text + ": expected WIDTHxHEIGHT, e.g. 600x400");
  record.width = std::stoi(m[1]);
  record.height = std::stoi(m[2]);
  const std::string problem = video ? check_video_size(record.width, record.height)
                                    : check_frame_size(record.width, record.height);
  if (!problem.empty()) throw UsageError("--size " + text + ": " + problem);
}

void print_summary(const RecordResult& r, const std::string& what, const Options& o) {
  std::string targets = o.output;
  if (!o.frames.empty()) targets += (targets.empty() ? "" : " and ") + o.frames + "/";
  std::printf("%s: %s at %dx%d, %g fps -> %s\n", what.c_str(), count_of(r.frames, "frame").c_str(),
              r.width, r.height, r.fps, targets.c_str());
  if (!r.episodes.returns.empty())
    std::printf("mean_reward = %.2f +/- %.2f, mean_ep_length = %.1f over %s\n",
                r.episodes.mean_return(), r.episodes.std_return(), r.episodes.mean_length(),
                count_of(static_cast<int64_t>(r.episodes.returns.size()), "episode").c_str());
  if (r.interrupted) std::printf("interrupted: the video holds the frames recorded so far\n");
}

int run(const Options& o, Registry& registry) {
  load_plugin_options(o.plugins, registry);
  const int sources =
      !o.model.empty() + !o.config.empty() + !o.from_obs.empty() +
      (o.model.empty() && o.config.empty() && o.from_obs.empty() && !o.env_id.empty());
  if (sources != 1)
    throw UsageError(
        "record needs exactly one of --model FILE, --config CFG --policy P, "
        "--env ID --policy P, or --from-obs PATH --env ID");
  if (o.output.empty() && o.frames.empty())
    throw UsageError("record needs --output video.mp4 and/or --frames DIR");

  RecordOptions record;
  record.video_path = o.output;
  record.frames_dir = o.frames;
  record.episodes = o.episodes;
  record.seed = o.seed;
  record.fps = o.fps;
  record.overlay = !o.no_overlay;
  if (!o.size.empty()) parse_size(o.size, record, !o.output.empty());
  install_interrupt_handlers();
  record.keep_going = [] { return !interrupt_requested(); };

  if (!o.from_obs.empty()) {
    if (o.env_id.empty()) throw UsageError("--from-obs needs --env ID (the env that logged them)");
    EnvPtr env = env_by_id(o.env_id, registry, o.overrides);
    const RecordResult r = record_observations(*env, observation_log_files(o.from_obs), record);
    print_summary(r, "recorded observation log " + o.from_obs + " of " + o.env_id, o);
    return r.interrupted ? 130 : 0;
  }

  const std::string policy = o.policy.empty() ? (o.model.empty() ? "" : "model") : o.policy;
  if (policy == "model" && o.model.empty()) throw UsageError("--policy model needs --model FILE");
  if (policy.empty()) throw UsageError("without --model, choose a policy: --policy random");

  std::optional<ModelPlayer> player;  // statistics frozen; a per-agent run's whole team
  EnvPtr env;
  if (!o.model.empty()) {
    std::vector<std::string> overrides = o.overrides;
    add_model_env_override(o.env_id, overrides);
    player = load_model_player(o.model, registry, overrides, o.trust, o.zoo_env);
  } else if (!o.config.empty()) {
    const Experiment experiment = load_experiment(o.config, o.overrides, registry);
    env = make_env(experiment.env, registry, "", unix_time_now());
  } else {
    env = env_by_id(o.env_id, registry, o.overrides);
  }
  Env& played = player ? player->env() : *env;

  give_opponent_model(o.game, played, registry);
  PolicyFn act;
  std::function<void()> start_episode;  // a recurrent model's state reset
  if (policy == "model") {
    const bool deterministic = !o.stochastic;
    record.policy_label = player->label + (deterministic ? " deterministic" : " stochastic");
    // With the env's masks if any, the recurrent state if any.
    act = player->act(deterministic, &start_episode);
  } else {
    PolicyOptions options;
    options.seed = o.seed;
    if (o.green_time) options.settings["green_time"] = *o.green_time;
    NamedPolicy named = named_policy(policy, played, registry, options);
    act = std::move(named.act);
    record.policy_label = named.label;
  }
  const RecordResult r = record_episodes(played, act, record, start_episode);
  print_summary(r,
                "recorded " + count_of(static_cast<int64_t>(r.episodes.returns.size()), "episode") +
                    " of " + played.id() + " (" + record.policy_label + ")",
                o);
  return r.interrupted ? 130 : 0;
}

}  // namespace

Action add_record(CLI::App& app, Registry& registry) {
  auto options = std::make_shared<Options>();
  CLI::App* sub = app.add_subcommand(
      "record", "record a policy as an mp4 video (needs the ffmpeg program) and/or PNG frames");
  CLI::Option* model_option =
      sub->add_option("--model", options->model, "model.zip written by rlrun train");
  CLI::Option* zoo_option =
      sub->add_option("--zoo-model", options->zoo_model,
                      "an rl-baselines3-zoo run folder (<algo>/<env>_<n>/): its model on its env")
          ->excludes(model_option);
  add_zoo_model_choice_options(sub, zoo_option, options->zoo_choice);
  sub->add_option("--config", options->config,
                  "experiment file whose env to record (with --policy random)");
  sub->add_option("--set", options->overrides,
                  "override a value of --config, or of the model's config (a model file is "
                  "untrusted: this is how you vouch for a program or file it names; repeatable)")
      ->allow_extra_args(false);
  sub->add_option("--env", options->env_id,
                  "env id (with --policy random or --from-obs; with --model, the env to play: "
                  "needed for an SB3 model file)");
  sub->add_option("--policy", options->policy,
                  "model (default with --model), random, or one that comes with the env "
                  "(fixed-time: traffic task; scripted: grasp task)");
  sub->add_option("--green-time", options->green_time,
                  "green seconds per approach of --policy fixed-time")
      ->transform(integer_in(1));
  sub->add_option("--from-obs", options->from_obs,
                  "observation log to draw: a .npy file or a directory of .npy chunks (obs_log)");
  sub->add_option("--output,-o", options->output, "mp4 file to write (H.264, yuv420p)");
  sub->add_option("--frames", options->frames,
                  "also (or instead) write PNG frames into this directory");
  sub->add_option("--episodes", options->episodes, "number of episodes")->transform(integer_in(1));
  sub->add_option("--fps", options->fps,
                  "frames per second (default: the env's, e.g. 50 for CartPole)")
      ->check(positive_number(kMaxVideoFps));
  sub->add_option("--size", options->size,
                  "frame size WIDTHxHEIGHT (default: the env's, e.g. 600x400)");
  sub->add_option("--seed", options->seed, "seed of the first episode's reset (default 0)")
      ->check(seed_value());
  auto deterministic = std::make_shared<bool>(false);
  CLI::Option* det =
      sub->add_flag("--deterministic", *deterministic, "use the deterministic policy (default)");
  sub->add_flag("--stochastic", options->stochastic, "sample actions from the policy")
      ->excludes(det);
  sub->add_flag("--no-overlay", options->no_overlay, "no text (env id, episode, step, return)");
  add_plugin_option(sub, options->plugins);
  add_trust_option(sub, options->trust);
  add_game_opponent_options(sub, options->game);
  return [options, deterministic, &registry]() {
    add_game_opponent_overrides(options->game, options->overrides);
    options->zoo_env = resolve_zoo_model(options->zoo_model, options->zoo_choice, registry,
                                         options->model, options->env_id);
    return run(*options, registry);
  };
}

}  // namespace rlrun::cli
