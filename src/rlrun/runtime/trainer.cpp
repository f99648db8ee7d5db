#include "rlrun/runtime/trainer.hpp"

#include <unistd.h>

#include <atomic>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <memory>
#include <vector>

#include "rlrun/algos/algorithm.hpp"
#include "rlrun/core/errors.hpp"
#include "rlrun/env/vec_env.hpp"
#include "rlrun/runtime/callback.hpp"
#include "rlrun/runtime/env_factory.hpp"
#include "rlrun/runtime/env_statistics.hpp"
#include "rlrun/runtime/log_sinks.hpp"
#include "rlrun/runtime/model_file.hpp"
#include "rlrun/runtime/progress_bar.hpp"
#include "rlrun/runtime/run_directory.hpp"

namespace rlrun {

namespace {

std::atomic<bool> g_interrupted{false};

void on_signal(int) { g_interrupted.store(true); }

// Writes every message to stdout and log.txt.
class RunLog {
 public:
  explicit RunLog(const std::string& path) : file_(path, std::ios::app) {
    if (!file_) throw RuntimeFailure("cannot write " + path);
  }
  void line(const std::string& text) {
    std::cout << text << std::endl;
    file_ << text << std::endl;
  }
  std::ofstream& file() { return file_; }

 private:
  std::ofstream file_;
};

}  // namespace

void install_interrupt_handlers() {
  std::signal(SIGINT, on_signal);
  std::signal(SIGTERM, on_signal);
}

bool interrupt_requested() { return g_interrupted.load(); }

TrainOutcome train_experiment(const Experiment& experiment, const Registry& registry) {
  TrainOutcome outcome;
  const RunConfig& run = experiment.run;
  outcome.run_dir = create_run_directory(run.out_dir, run.name, run.seed);
  write_text_atomic(outcome.run_dir + "/config.yaml", dump_yaml(experiment.resolved));
  RunLog log(outcome.run_dir + "/log.txt");
  log.line("rlrun " RLRUN_VERSION ": training " + experiment.algo_id + " on " + experiment.env.id +
           " for " + std::to_string(run.total_timesteps) + " steps (seed " +
           std::to_string(run.seed) + ", " + std::to_string(experiment.env.section.n_envs) +
           " envs) -> " + outcome.run_dir);

  // obs_log taps the env's own observations of one training env (obs_log_callback.hpp).
  const int tap_env = experiment.obs_log.freq > 0 ? experiment.obs_log.env : -1;
  VecEnv env = make_vec_env(experiment.env, registry, experiment.env.section.n_envs,
                            outcome.run_dir, tap_env);
  share_model_statistics(env);  // one set of normalisation statistics, like VecNormalize
  env.seed(run.seed);
  const AlgorithmSetup setup{env.observation_space(), env.action_space(), env.num_envs(), run.seed};
  const AlgorithmEntry& entry =
      registry.algorithm(experiment.algo_id, experiment.algo_node.child("id"));
  std::unique_ptr<Algorithm> algorithm;
  try {
    algorithm = entry.make(experiment.algo_node, setup);
  } catch (const std::invalid_argument& e) {
    experiment.algo_node.fail(e.what());
  }

  const bool tty = isatty(STDOUT_FILENO) != 0;
  ProgressBar bar(run.total_timesteps, tty);
  Logger logger;
  logger.add_sink(std::make_unique<CsvSink>(outcome.run_dir + "/progress.csv"));
  logger.add_sink(std::make_unique<ConsoleTableSink>(std::cout, run.console_interval,
                                                     [&bar] { bar.clear(); }));
  logger.add_sink(std::make_unique<ConsoleTableSink>(log.file(), 0.0));

  // Model files carry the normalisation statistics of training env 0 (shared by all envs).
  const auto save_with_statistics = [&](const std::string& path) {
    TensorMap statistics;
    save_model_statistics(env.env(0), statistics);
    save_model(path, *algorithm, experiment, env.observation_space(), env.action_space(),
               statistics);
  };
  TrainingContext context{experiment,
                          registry,
                          outcome.run_dir,
                          *algorithm,
                          env,
                          &logger,
                          [&](const std::string& message) {
                            bar.clear();
                            log.line(message);
                          },
                          save_with_statistics,
                          save_with_statistics};
  const std::vector<std::unique_ptr<Callback>> callbacks = make_callbacks(context);

  TrainingHooks hooks;
  hooks.logger = &logger;
  hooks.log_interval = run.log_interval.value_or(0);
  hooks.on_step = [&](int64_t num_timesteps) {
    bar.update(num_timesteps);
    bool continue_training = true;  // SB3 CallbackList: every callback runs, any can stop
    for (const auto& callback : callbacks)
      continue_training = callback->on_step(num_timesteps) && continue_training;
    return continue_training && !interrupt_requested();
  };

  const auto start = std::chrono::steady_clock::now();
  algorithm->learn(env, run.total_timesteps, hooks);
  outcome.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  outcome.timesteps = algorithm->num_timesteps();
  for (const auto& callback : callbacks) {
    callback->on_training_end(outcome.timesteps);
    if (outcome.stop_reason.empty()) outcome.stop_reason = callback->stop_reason();
  }
  bar.finish();
  logger.flush();
  outcome.interrupted = interrupt_requested();
  outcome.model_path = outcome.run_dir + "/model.zip";
  save_with_statistics(outcome.model_path);
  if (!outcome.stop_reason.empty()) log.line("stopped early: " + outcome.stop_reason);
  char summary[256];
  std::snprintf(summary, sizeof summary, "%s %lld steps in %.2f s (%.0f steps/s); model saved to %s",
                outcome.interrupted ? "interrupted after" : "trained",
                static_cast<long long>(outcome.timesteps), outcome.wall_seconds,
                static_cast<double>(outcome.timesteps) / std::max(outcome.wall_seconds, 1e-9),
                outcome.model_path.c_str());
  log.line(summary);
  return outcome;
}

}  // namespace rlrun
