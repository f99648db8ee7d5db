#include "rlrun/runtime/trainer.hpp"

#include <unistd.h>

#include <atomic>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <optional>
#include <vector>

#include "rlrun/algos/algorithm.hpp"
#include "rlrun/core/errors.hpp"
#include "rlrun/env/vec_env.hpp"
#include "rlrun/runtime/callback.hpp"
#include "rlrun/runtime/checkpoint_callback.hpp"
#include "rlrun/runtime/env_factory.hpp"
#include "rlrun/runtime/env_statistics.hpp"
#include "rlrun/runtime/init_from.hpp"
#include "rlrun/runtime/log_sinks.hpp"
#include "rlrun/runtime/model_budget.hpp"
#include "rlrun/runtime/model_file.hpp"
#include "rlrun/runtime/non_finite_check.hpp"
#include "rlrun/runtime/progress_bar.hpp"
#include "rlrun/runtime/run_directory.hpp"
#include "rlrun/runtime/run_log_marks.hpp"

namespace rlrun {

namespace fs = std::filesystem;

namespace {

std::atomic<int> g_interrupts{0};

void on_signal(int) {
  // write(2) is async-signal-safe; iostreams are not.
  static const char first[] =
      "\nrlrun: stopping at the next safe point to write a checkpoint "
      "(Ctrl-C again stops at once, without one)\n";
  if (g_interrupts.fetch_add(1) == 0) {
    const ssize_t ignored = write(STDERR_FILENO, first, sizeof first - 1);
    (void)ignored;
  }
}

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

// Where the training state lives inside a checkpoint (core/state_dict.hpp keys).
constexpr const char* kAlgoState = "algo";
constexpr const char* kEnvState = "env";
constexpr const char* kCallbackState = "callbacks";
constexpr const char* kLoggerState = "logger";
constexpr const char* kFileMarks = "files";

void write_pending_log(StateWriter out, const LogRow& row) {
  out.put_int("count", static_cast<int64_t>(row.size()));
  int i = 0;
  for (const auto& [key, value] : row) {
    StateWriter entry = out.sub(std::to_string(i++));
    entry.put_string("key", key);
    entry.put_double("value", value);
  }
}

LogRow read_pending_log(const StateReader& in) {
  LogRow row;
  const int64_t count = in.get_int("count");
  for (int64_t i = 0; i < count; ++i) {
    const StateReader entry = in.sub(std::to_string(i));
    row[entry.get_string("key")] = entry.get_double("value");
  }
  return row;
}

// Removes a new run directory unless dismissed: a run that fails while being set up (bad
// --init-from model, env that cannot start) leaves no half-made directory behind, so the next
// attempt gets the same name.
class NewRunDirectoryGuard {
 public:
  explicit NewRunDirectoryGuard(std::string path) : path_(std::move(path)) {}
  ~NewRunDirectoryGuard() {
    if (path_.empty()) return;
    std::error_code ec;
    fs::remove_all(path_, ec);
  }
  void dismiss() { path_.clear(); }

 private:
  std::string path_;
};

std::string checkpoint_name(const std::string& run_dir, int64_t num_timesteps) {
  return run_dir + "/checkpoints/step_" + std::to_string(num_timesteps) + ".zip";
}

}  // namespace

void install_interrupt_handlers() {
  std::signal(SIGINT, on_signal);
  std::signal(SIGTERM, on_signal);
}

bool interrupt_requested() { return g_interrupts.load() > 0; }
int interrupt_count() { return g_interrupts.load(); }

std::string run_dir_of_checkpoint(const std::string& checkpoint) {
  return fs::path(checkpoint).parent_path().parent_path().string();
}

std::string resolve_resume_checkpoint(const std::string& run_dir_or_checkpoint) {
  std::error_code ec;
  if (fs::is_directory(run_dir_or_checkpoint, ec)) {
    const std::vector<std::string> found =
        CheckpointCallback::list_checkpoints(run_dir_or_checkpoint + "/checkpoints");
    if (found.empty())
      throw UsageError("cannot resume " + run_dir_or_checkpoint +
                       ": it has no checkpoints/step_<N>.zip (checkpoints are written every "
                       "checkpoint.freq steps and when training is interrupted)");
    return found.back();
  }
  if (!fs::is_regular_file(run_dir_or_checkpoint, ec))
    throw UsageError("cannot resume " + run_dir_or_checkpoint +
                     ": no such run directory or checkpoint file");
  if (fs::path(run_dir_or_checkpoint).parent_path().filename() != "checkpoints")
    throw UsageError("cannot resume from " + run_dir_or_checkpoint +
                     ": only checkpoints (<run_dir>/checkpoints/step_<N>.zip) hold a training "
                     "state; to start a new run from a model's weights use --init-from");
  return run_dir_or_checkpoint;
}

TrainOutcome train_experiment(const Experiment& experiment, const Registry& registry,
                              const std::string& resume_checkpoint) {
  TrainOutcome outcome;
  const RunConfig& run = experiment.run;
  const bool resuming = !resume_checkpoint.empty();
  std::optional<ModelFile> checkpoint;
  if (resuming) {
    checkpoint = read_checkpoint(resume_checkpoint, experiment, registry);  // model_budget.hpp
    if (checkpoint->training_state.empty())
      throw UsageError("cannot resume from " + resume_checkpoint +
                       ": it holds no training state (a model file, not a checkpoint)");
    if (checkpoint->meta.algorithm != experiment.algo_id)
      throw UsageError("cannot resume from " + resume_checkpoint + ": it was written by " +
                       checkpoint->meta.algorithm + ", the run's config trains " +
                       experiment.algo_id);
    outcome.run_dir = run_dir_of_checkpoint(resume_checkpoint);
    // The files go back to where the checkpoint left them (rows written after it would
    // otherwise appear twice).
    restore_log_marks(StateReader(checkpoint->training_state,
                                  std::string(kTrainingStatePrefix) + kFileMarks + "/"),
                      outcome.run_dir);
  } else {
    outcome.run_dir = create_run_directory(run.out_dir, run.name, run.seed);
  }
  NewRunDirectoryGuard new_run_guard(resuming ? "" : outcome.run_dir);
  std::error_code no_marker;
  std::filesystem::remove(outcome.run_dir + "/" + kFinishedMarker, no_marker);  // training again
  write_text_atomic(outcome.run_dir + "/config.yaml", dump_yaml(experiment.resolved));
  RunLog log(outcome.run_dir + "/log.txt");
  if (resuming)
    log.line("rlrun " RLRUN_VERSION ": resuming " + experiment.algo_id + " on " +
             experiment.env.id + " from " + resume_checkpoint + " (step " +
             std::to_string(checkpoint->meta.num_timesteps) + " of " +
             std::to_string(run.total_timesteps) + ")");
  else
    log.line("rlrun " RLRUN_VERSION ": training " + experiment.algo_id + " on " +
             experiment.env.id + " for " + std::to_string(run.total_timesteps) + " steps (seed " +
             std::to_string(run.seed) + ", " + std::to_string(experiment.env.section.n_envs) +
             " envs) -> " + outcome.run_dir);

  // obs_log taps the env's own observations of one training env (obs_log_callback.hpp).
  const int tap_env = experiment.obs_log.freq > 0 ? experiment.obs_log.env : -1;
  VecEnv env = make_vec_env(experiment.env, registry, experiment.env.section.n_envs,
                            outcome.run_dir, tap_env, /*append_monitor=*/resuming);
  share_model_statistics(env);  // one set of normalisation statistics, like VecNormalize
  if (!resuming) env.seed(run.seed);
  const AlgorithmSetup setup{env.observation_space(), env.action_space(), env.num_envs(), run.seed};
  const AlgorithmEntry& entry =
      registry.algorithm(experiment.algo_id, experiment.algo_node.child("id"));
  std::unique_ptr<Algorithm> algorithm;
  try {
    algorithm = entry.make(experiment.algo_node, setup);
  } catch (const std::invalid_argument& e) {
    experiment.algo_node.fail(e.what());
  }

  const auto training_state = [&](const char* part) {
    return StateReader(checkpoint->training_state, std::string(kTrainingStatePrefix) + part + "/");
  };
  if (!resuming && !run.init_from.empty())
    log.line(initialize_from_model(run.init_from, *algorithm, env));
  if (resuming) {
    try {
      algorithm->load(checkpoint->tensors);
      algorithm->load_training_state(training_state(kAlgoState));
      env.read_state(training_state(kEnvState));
    } catch (const std::exception& e) {
      throw RuntimeFailure("cannot resume from " + resume_checkpoint + ": " + e.what());
    }
  }

  const bool tty = isatty(STDOUT_FILENO) != 0;
  ProgressBar bar(run.total_timesteps, tty);
  Logger logger;
  auto csv_sink = std::make_unique<CsvSink>(outcome.run_dir + "/progress.csv", resuming);
  CsvSink& progress_csv = *csv_sink;
  logger.add_sink(std::move(csv_sink));
  logger.add_sink(std::make_unique<ConsoleTableSink>(std::cout, run.console_interval,
                                                     [&bar] { bar.clear(); }));
  logger.add_sink(std::make_unique<ConsoleTableSink>(log.file(), 0.0));

  // The files a checkpoint marks (runtime/run_log_marks.hpp).
  std::vector<std::string> appended_files{"progress.csv"};
  for (int i = 0; i < env.num_envs(); ++i) appended_files.push_back(monitor_file_name(i));
  if (experiment.eval.freq > 0) appended_files.push_back("evaluations.csv");

  std::vector<std::unique_ptr<Callback>> callbacks;
  std::string last_checkpoint = resuming ? resume_checkpoint : "";
  // A NaN or inf stops the run, naming the step and the quantity (non_finite_check.hpp).
  const auto stop_diverged = [&](const std::string& problem) {
    std::string message = "training diverged at step " +
                          std::to_string(algorithm->num_timesteps()) + ": " + problem + ".";
    message += last_checkpoint.empty()
                   ? " No checkpoint was written (set checkpoint.freq to keep one)."
                   : " The last good checkpoint is " + last_checkpoint + ".";
    log.file() << "error: " << message << std::endl;  // main prints it on stderr
    throw RuntimeFailure(message);
  };
  // Never write a non-finite model.
  const auto require_finite_model = [&](const TensorMap& tensors) {
    const std::string problem = describe_non_finite(tensors);
    if (!problem.empty()) stop_diverged(problem);
  };
  // Model files carry the normalisation statistics of training env 0 (shared by all envs).
  const auto save_with_statistics = [&](const std::string& path) {
    TensorMap model;
    algorithm->save(model);
    require_finite_model(model);
    TensorMap statistics;
    save_model_statistics(env.env(0), statistics);
    save_model(path, *algorithm, experiment, env.observation_space(), env.action_space(),
               statistics);
  };
  // Envs that cannot snapshot themselves (plugins, external simulators) get model-only
  // checkpoints, as SB3's CheckpointCallback writes; --resume refuses those with the reason.
  const bool resumable = env.can_save_state();
  if (!resumable && experiment.checkpoint.freq > 0)
    log.line("note: " + experiment.env.id +
             " cannot save its state, so checkpoints hold the model only and the run cannot be "
             "resumed exactly");
  const auto save_checkpoint = [&](const std::string& path) {
    TensorMap model;
    algorithm->save(model);
    require_finite_model(model);
    TensorMap extra;
    save_model_statistics(env.env(0), extra);
    if (!resumable) {
      save_model(path, *algorithm, experiment, env.observation_space(), env.action_space(), extra);
      return;
    }
    StateWriter state(extra, kTrainingStatePrefix);
    StateWriter algo_state = state.sub(kAlgoState);
    algorithm->save_training_state(algo_state);
    StateWriter env_state = state.sub(kEnvState);
    env.write_state(env_state);
    StateWriter callback_state = state.sub(kCallbackState);
    callback_state.put_int("count", static_cast<int64_t>(callbacks.size()));
    for (size_t i = 0; i < callbacks.size(); ++i) {
      StateWriter one = callback_state.sub(std::to_string(i));
      callbacks[i]->write_state(one);
      callbacks[i]->flush();
    }
    write_pending_log(state.sub(kLoggerState), logger.pending());
    progress_csv.flush();
    write_log_marks(state.sub(kFileMarks), outcome.run_dir, appended_files);
    fs::create_directories(fs::path(path).parent_path());
    save_model(path, *algorithm, experiment, env.observation_space(), env.action_space(), extra);
    last_checkpoint = path;
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
                          save_checkpoint,
                          resuming};
  callbacks = make_callbacks(context);
  if (resuming) {
    const StateReader callback_state = training_state(kCallbackState);
    if (callback_state.get_int("count") != static_cast<int64_t>(callbacks.size()))
      throw RuntimeFailure("cannot resume from " + resume_checkpoint +
                           ": it was written with other callbacks (eval/checkpoint/obs_log/"
                           "video sections) than the run's config.yaml turns on");
    for (size_t i = 0; i < callbacks.size(); ++i)
      callbacks[i]->read_state(callback_state.sub(std::to_string(i)));
    logger.restore_pending(read_pending_log(training_state(kLoggerState)));
  }

  TrainingHooks hooks;
  hooks.logger = &logger;
  hooks.log_interval = run.log_interval.value_or(0);
  hooks.on_step = [&](int64_t num_timesteps) {
    bar.update(num_timesteps);
    bool continue_training = true;  // SB3 CallbackList: every callback runs, any can stop
    for (const auto& callback : callbacks)
      continue_training = callback->on_step(num_timesteps) && continue_training;
    return continue_training && g_interrupts.load() < 2;
  };
  hooks.on_log = [&](int64_t) {
    // Parameters once per log row: cheap next to the updates between rows.
    TensorMap model;
    algorithm->save(model);
    require_finite_model(model);
  };
  hooks.at_safe_point = [&](int64_t num_timesteps) {
    const std::string problem = describe_non_finite(logger.pending());
    if (!problem.empty()) stop_diverged(problem);
    for (const auto& callback : callbacks) callback->at_safe_point(num_timesteps);
    if (!interrupt_requested()) return true;
    if (!resumable) return false;  // nothing to resume from: just stop, model.zip follows
    const std::string path = checkpoint_name(outcome.run_dir, num_timesteps);
    if (last_checkpoint != path) save_checkpoint(path);
    outcome.checkpoint_path = path;
    return false;
  };

  new_run_guard.dismiss();  // set up: from here on the run's files are worth keeping
  const auto start = std::chrono::steady_clock::now();
  algorithm->learn(env, run.total_timesteps, hooks);
  outcome.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  outcome.timesteps = algorithm->num_timesteps();
  outcome.interrupted = interrupt_requested();
  for (const auto& callback : callbacks) {
    callback->on_training_end(outcome.timesteps, !outcome.checkpoint_path.empty());
    if (outcome.stop_reason.empty()) outcome.stop_reason = callback->stop_reason();
  }
  bar.finish();
  logger.flush();
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
  if (!outcome.interrupted)  // the last file written: `rlrun sweep run` skips such runs
    write_text_atomic(outcome.run_dir + "/" + kFinishedMarker,
                      "timesteps " + std::to_string(outcome.timesteps) + "\n");
  if (outcome.interrupted) {
    if (!outcome.checkpoint_path.empty())
      log.line("checkpoint saved to " + outcome.checkpoint_path +
               "; resume with: rlrun train --resume " + outcome.run_dir);
    else if (!last_checkpoint.empty())
      log.line("stopped without a checkpoint; the last one is " + last_checkpoint +
               " (rlrun train --resume " + outcome.run_dir + " continues from it)");
  }
  return outcome;
}

}  // namespace rlrun
