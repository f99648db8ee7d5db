// rlrun eval --model FILE [--episodes N] [--seed S] [--deterministic|--stochastic] [--csv FILE]
//            [--record video.mp4]
#include <cstdio>
#include <fstream>
#include <iostream>
#include <memory>

#include "commands.hpp"
#include "plugin_option.hpp"
#include "rlrun/core/errors.hpp"
#include "rlrun/runtime/builtins.hpp"
#include "rlrun/runtime/env_factory.hpp"
#include "rlrun/runtime/evaluator.hpp"
#include "rlrun/runtime/model_file.hpp"
#include "rlrun/runtime/recorder.hpp"

namespace rlrun::cli {

Action add_eval(CLI::App& app) {
  struct Options {
    std::string model;
    int episodes = 10;
    uint64_t seed = 0;
    bool stochastic = false;
    std::string csv;
    std::string record;  // mp4 of the evaluation episodes
    std::vector<std::string> plugins;
  };
  auto options = std::make_shared<Options>();
  CLI::App* sub = app.add_subcommand("eval", "evaluate a trained model (needs only the model file)");
  sub->add_option("--model", options->model, "model.zip written by rlrun train")->required();
  sub->add_option("--episodes", options->episodes, "number of episodes")->check(CLI::PositiveNumber);
  sub->add_option("--seed", options->seed, "seed of the first episode's reset");
  auto deterministic = std::make_shared<bool>(false);
  CLI::Option* det = sub->add_flag("--deterministic", *deterministic,
                                   "use the deterministic policy (default)");
  sub->add_flag("--stochastic", options->stochastic, "sample actions from the policy")->excludes(det);
  sub->add_option("--csv", options->csv, "also write one row per episode (episode,return,length)");
  add_plugin_option(sub, options->plugins);
  sub->add_option("--record", options->record,
                  "also record the episodes to this mp4 (same episodes and numbers; needs ffmpeg)");
  return [options, deterministic]() {
    load_plugin_options(options->plugins);  // model files name their plugins too
    const Registry& registry = builtin_registry();
    const ModelFile model = read_model(options->model);
    const Experiment experiment = experiment_from_model(model, registry);
    EnvPtr env = make_model_env(model, experiment, registry);  // normalisation stats frozen
    auto algorithm = algorithm_from_model(model, experiment, registry, env->observation_space(),
                                          env->action_space());
    EvalResult r;
    if (options->record.empty()) {
      r = evaluate_policy(*algorithm, *env, options->episodes, !options->stochastic, options->seed);
    } else {
      // record_episodes runs exactly evaluate_policy's episodes, drawing every frame.
      RecordOptions record;
      record.video_path = options->record;
      record.episodes = options->episodes;
      record.seed = options->seed;
      record.policy_label = model.meta.algorithm + (options->stochastic ? " stochastic" : " deterministic");
      const bool deterministic = !options->stochastic;
      const RecordResult recorded = record_episodes(
          *env,
          [&](const Eigen::MatrixXf& obs, Eigen::MatrixXf& action) {
            algorithm->predict(obs, deterministic, action);
          },
          record);
      r = recorded.episodes;
      std::printf("recorded %lld frames at %dx%d -> %s\n", static_cast<long long>(recorded.frames),
                  recorded.width, recorded.height, options->record.c_str());
    }
    if (!options->csv.empty()) {
      std::ofstream csv(options->csv, std::ios::trunc);
      if (!csv) throw RuntimeFailure("cannot write " + options->csv);
      csv << "episode,return,length" << (r.successes.empty() ? "" : ",is_success") << "\n";
      for (size_t i = 0; i < r.returns.size(); ++i) {
        csv << i << ',' << r.returns[i] << ',' << r.lengths[i];
        if (!r.successes.empty()) csv << ',' << (i < r.successes.size() ? r.successes[i] : 0.0);
        csv << '\n';
      }
    }
    std::printf("%s on %s, %d episodes (%s): mean_reward = %.2f +/- %.2f, mean_ep_length = %.1f\n",
                model.meta.algorithm.c_str(), experiment.env.id.c_str(), options->episodes,
                options->stochastic ? "stochastic" : "deterministic", r.mean_return(),
                r.std_return(), r.mean_length());
    if (!r.successes.empty()) {
      double s = 0;
      for (double x : r.successes) s += x;
      std::printf("success_rate = %.3f\n", s / static_cast<double>(r.successes.size()));
    }
    return 0;
  };
}

}  // namespace rlrun::cli
