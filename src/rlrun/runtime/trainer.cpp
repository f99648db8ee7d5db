#include "rlrun/runtime/trainer.hpp"

#include <unistd.h>

#include <atomic>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <limits>
#include <memory>

#include "rlrun/algos/algorithm.hpp"
#include "rlrun/core/errors.hpp"
#include "rlrun/env/vec_env.hpp"
#include "rlrun/runtime/env_factory.hpp"
#include "rlrun/runtime/evaluator.hpp"
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

// EvalCallback (SB3 common/callbacks.py) counting TOTAL env steps: evaluates when
// num_timesteps crosses a multiple of `freq`, appends to evaluations.csv, keeps best_model.zip.
class PeriodicEvaluator {
 public:
  PeriodicEvaluator(const Experiment& experiment, const Registry& registry, const std::string& run_dir,
                    const Space& obs_space, const Space& act_space)
      : experiment_(experiment),
        run_dir_(run_dir),
        obs_space_(obs_space),
        act_space_(act_space),
        env_(make_env(experiment.env, registry, "", unix_time_now())),
        next_(experiment.eval.freq) {
    csv_.open(run_dir + "/evaluations.csv", std::ios::trunc);
    csv_ << "timesteps,mean_reward,std_reward,mean_ep_length,success_rate\n";
    csv_.flush();
  }

  // Returns the message to log when an evaluation ran.
  std::string maybe_evaluate(Algorithm& algorithm, int64_t num_timesteps) {
    if (num_timesteps < next_) return "";
    while (next_ <= num_timesteps) next_ += experiment_.eval.freq;
    // Evaluation env seeded apart from the training envs (seed + n_envs onwards).
    const uint64_t seed = experiment_.run.seed + static_cast<uint64_t>(experiment_.env.section.n_envs) +
                          static_cast<uint64_t>(evaluations_++);
    const EvalResult r = evaluate_policy(algorithm, *env_, experiment_.eval.n_episodes,
                                         experiment_.eval.deterministic, seed);
    double success = std::numeric_limits<double>::quiet_NaN();
    if (!r.successes.empty()) {
      success = 0;
      for (double s : r.successes) success += s;
      success /= static_cast<double>(r.successes.size());
    }
    char line[256];
    std::snprintf(line, sizeof line, "%lld,%.6g,%.6g,%.6g,", static_cast<long long>(num_timesteps),
                  r.mean_return(), r.std_return(), r.mean_length());
    csv_ << line;
    if (!std::isnan(success)) csv_ << success;
    csv_ << '\n';
    csv_.flush();
    std::string message = "eval at " + std::to_string(num_timesteps) + " steps: return " +
                          format_log_value(r.mean_return()) + " +/- " +
                          format_log_value(r.std_return()) + ", length " +
                          format_log_value(r.mean_length());
    if (r.mean_return() > best_) {
      best_ = r.mean_return();
      save_model(run_dir_ + "/best_model.zip", algorithm, experiment_, obs_space_, act_space_);
      message += " (new best, saved best_model.zip)";
    }
    return message;
  }

 private:
  const Experiment& experiment_;
  std::string run_dir_;
  Space obs_space_, act_space_;
  EnvPtr env_;
  int64_t next_;
  int evaluations_ = 0;
  double best_ = -std::numeric_limits<double>::infinity();
  std::ofstream csv_;
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

  VecEnv env = make_vec_env(experiment.env, registry, experiment.env.section.n_envs, outcome.run_dir);
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

  std::unique_ptr<PeriodicEvaluator> evaluator;
  if (experiment.eval.freq > 0)
    evaluator = std::make_unique<PeriodicEvaluator>(experiment, registry, outcome.run_dir,
                                                    env.observation_space(), env.action_space());

  TrainingHooks hooks;
  hooks.logger = &logger;
  hooks.log_interval = run.log_interval.value_or(0);
  hooks.on_step = [&](int64_t num_timesteps) {
    bar.update(num_timesteps);
    if (evaluator) {
      const std::string message = evaluator->maybe_evaluate(*algorithm, num_timesteps);
      if (!message.empty()) {
        bar.clear();
        log.line(message);
      }
    }
    return !interrupt_requested();
  };

  const auto start = std::chrono::steady_clock::now();
  algorithm->learn(env, run.total_timesteps, hooks);
  outcome.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  bar.finish();
  logger.flush();
  outcome.timesteps = algorithm->num_timesteps();
  outcome.interrupted = interrupt_requested();
  outcome.model_path = outcome.run_dir + "/model.zip";
  save_model(outcome.model_path, *algorithm, experiment, env.observation_space(), env.action_space());
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
