#include "rlrun/runtime/run/trainer.hpp"

#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>
#include <optional>
#include <vector>

#include "rlrun/algos/algorithm.hpp"
#include "rlrun/core/dir_handle.hpp"
#include "rlrun/core/errors.hpp"
#include "rlrun/core/interrupt.hpp"
#include "rlrun/core/plural.hpp"
#include "rlrun/core/zip_archive.hpp"
#include "rlrun/env/agent_seats.hpp"
#include "rlrun/env/vec_env.hpp"
#include "rlrun/runtime/experiment/env_factory.hpp"
#include "rlrun/runtime/experiment/env_statistics.hpp"
#include "rlrun/runtime/io/log_sinks.hpp"
#include "rlrun/runtime/io/model_file.hpp"
#include "rlrun/runtime/io/non_finite_check.hpp"
#include "rlrun/runtime/io/run_directory.hpp"
#include "rlrun/runtime/io/run_lock.hpp"
#include "rlrun/runtime/io/run_log.hpp"
#include "rlrun/runtime/io/run_log_marks.hpp"
#include "rlrun/runtime/io/tensorboard/learning_curve_image.hpp"
#include "rlrun/runtime/io/tensorboard/tensorboard_log.hpp"
#include "rlrun/runtime/run/init_from.hpp"
#include "rlrun/runtime/run/per_agent_training.hpp"
#include "rlrun/runtime/run/progress_bar.hpp"
#include "rlrun/runtime/run/resume_point.hpp"
#include "rlrun/runtime/run/training_callbacks.hpp"
#include "rlrun/runtime/run/training_state_io.hpp"

namespace rlrun {

namespace fs = std::filesystem;

namespace trainer_detail {

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

// The files a run appends to, which a checkpoint marks (runtime/io/run_log_marks.hpp).
std::vector<std::string> appended_files(const Experiment& experiment) {
  std::vector<std::string> files{"progress.csv"};
  for (int i = 0; i < experiment.env.section.n_envs; ++i) files.push_back(monitor_file_name(i));
  if (experiment.eval.freq > 0) files.push_back("evaluations.csv");
  return files;
}

// checkpoints/<this>: what CheckpointCallback writes too.
std::string checkpoint_name(int64_t num_timesteps) {
  return "step_" + std::to_string(num_timesteps) + ".zip";
}

// One training run, in the order it happens: open the run directory (new, or the resumed
// run's, locked), build envs, algorithm and logging, restore a checkpoint's state, run the
// loop (callbacks, checkpoints, Ctrl-C), finish (model.zip, summary, finished marker).
class TrainingRun {
 public:
  TrainingRun(const Experiment& experiment, const Registry& registry,
              const ExecutionContext& execution, const std::vector<std::string>& resume_from,
              EvaluationListener on_evaluation)
      : experiment_(experiment),
        registry_(registry),
        execution_(execution),
        resuming_(!resume_from.empty()),
        on_evaluation_(std::move(on_evaluation)) {
    open_run_directory(resume_from);
    build();
    if (resuming_) restore();
    new_run_guard_->dismiss();  // set up: from here on the run's files are worth keeping
  }

  // Trains until the run's total env steps reach `total_timesteps`; may be called again to
  // continue (TrainingSession). `extra`: callbacks of the caller, after the config's.
  TrainOutcome run(int64_t total_timesteps,
                   const std::vector<std::unique_ptr<Callback>>& extra = {});
  TrainingContext& context() { return *context_; }
  int64_t num_timesteps() const { return algorithm_->num_timesteps(); }

 private:
  void open_run_directory(const std::vector<std::string>& resume_from);
  void announce();
  void build();
  void build_logging();
  void announce_agents();
  void build_tensorboard_log();
  void restore();
  TrainingHooks hooks();
  bool at_safe_point(int64_t num_timesteps);
  void save_model(const std::string& name);
  void save_checkpoint(const std::string& name);
  TensorMap finite_model_tensors();
  [[noreturn]] void stop_diverged(const std::string& problem);
  void finish();

  const Experiment& experiment_;
  const Registry& registry_;
  const ExecutionContext execution_;
  const bool resuming_;
  TrainOutcome outcome_;
  std::optional<DirHandle> dir_;  // the run directory, held open (core/dir_handle.hpp)
  std::optional<RunLock> lock_;
  std::optional<NewRunDirectoryGuard> new_run_guard_;
  std::optional<ResumePoint> resume_;
  std::optional<RunLog> log_;
  std::optional<VecEnv> env_;
  std::unique_ptr<Algorithm> algorithm_;
  std::optional<ProgressBar> bar_;
  Logger logger_;
  CsvSink* progress_csv_ = nullptr;
  TensorBoardLog* tensorboard_ = nullptr;  // owned by logger_; null without run.tensorboard_log
  std::optional<TrainingContext> context_;
  std::vector<std::unique_ptr<Callback>> callbacks_;
  // run()'s caller's callbacks (not part of the config: not in checkpoints).
  const std::vector<std::unique_ptr<Callback>>* extra_callbacks_ = nullptr;
  std::string last_checkpoint_;
  bool resumable_ = false;  // the envs can save their state: checkpoints resume exactly
  EvaluationListener on_evaluation_;
};

// A new run gets a fresh directory; a resumed one its own, cut back to the checkpoint. Either
// is held open (a resumed one may come from anyone: it must be a directory, not a link, and so
// must checkpoints/; core/dir_handle.hpp) and locked for this process (a second `--resume` of
// the same run is refused).
void TrainingRun::open_run_directory(const std::vector<std::string>& resume_from) {
  const RunConfig& run = experiment_.run;
  if (resuming_) {
    outcome_.run_dir = run_dir_of_checkpoint(resume_from.front());
    dir_ = DirHandle::open(outcome_.run_dir);
    lock_.emplace(*dir_);
    remove_stale_temporaries(*dir_);
    resume_ = open_resume_point(resume_from, experiment_, registry_);
    // The files go back to where the checkpoint left them (rows written after it would
    // otherwise appear twice).
    restore_log_marks(training_state_reader(resume_->checkpoint, kFileMarks), *dir_,
                      appended_files(experiment_));
  } else {
    outcome_.run_dir = create_run_directory(run.out_dir, run.name, run.seed);
    new_run_guard_.emplace(outcome_.run_dir);
    dir_ = DirHandle::open(outcome_.run_dir);
    lock_.emplace(*dir_);
  }
  if (!new_run_guard_) new_run_guard_.emplace("");
  dir_->remove(kFinishedMarker);  // training again
  dir_->write_atomic("config.yaml", dump_yaml(experiment_.resolved));
  // Not through a link (core/checked_file.hpp); on the console unless run.verbose is 0.
  log_.emplace(outcome_.run_dir + "/log.txt", experiment_.run.verbose > 0);
  announce();
}

void TrainingRun::announce() {
  const RunConfig& run = experiment_.run;
  if (!resuming_) {
    log_->line("rlrun " RLRUN_VERSION ": training " + experiment_.algo.id + " on " +
               experiment_.env.id + " for " + count_of(run.total_timesteps, "step") + " (seed " +
               std::to_string(run.seed) + ", " + count_of(experiment_.env.section.n_envs, "env") +
               ", " + count_of(execution_.threads(), "thread") + ") -> " + outcome_.run_dir);
    return;
  }
  for (const std::string& skipped : resume_->skipped)
    log_->line("note: skipping checkpoint " + skipped);
  log_->line("rlrun " RLRUN_VERSION ": resuming " + experiment_.algo.id + " on " +
             experiment_.env.id + " from " + resume_->path + " (step " +
             std::to_string(resume_->checkpoint.meta.num_timesteps) + " of " +
             std::to_string(run.total_timesteps) + ", " + count_of(execution_.threads(), "thread") +
             ")");
}

void TrainingRun::build() {
  // obs_log taps the env's own observations of one training env (obs_log_callback.hpp).
  const int tap_env = experiment_.obs_log.freq > 0 ? experiment_.obs_log.env : -1;
  env_.emplace(make_vec_env(experiment_.env, registry_, experiment_.env.section.n_envs,
                            outcome_.run_dir, tap_env, /*append_monitor=*/resuming_));
  share_model_statistics(*env_);  // one set of normalisation statistics, like VecNormalize
  if (!resuming_) env_->seed(experiment_.run.seed);
  env_->set_thread_pool(execution_.pool);
  const AlgorithmSetup setup{env_->observation_space(), env_->action_space(), env_->num_envs(),
                             experiment_.run.seed, execution_.pool};
  algorithm_ = make_algorithm(experiment_, registry_, setup);
  if (!resuming_ && !experiment_.run.init_from.empty())
    log_->line(initialize_from_model(experiment_.run.init_from, *algorithm_, *env_));
  // Envs that cannot snapshot themselves (plugins, external simulators) get model-only
  // checkpoints, as SB3's CheckpointCallback writes; --resume refuses those with the reason.
  announce_agents();
  resumable_ = env_->can_save_state();
  if (!resumable_ && experiment_.checkpoint.freq > 0)
    log_->line("note: " + experiment_.env.id +
               " cannot save its state, so checkpoints hold the model only and the run cannot "
               "be resumed exactly");
  build_logging();
}

// Several agents per env share the policy (each a column of the VecEnv): the counts in the
// console table are then of two kinds, said once before the first table.
void TrainingRun::announce_agents() {
  const int agents = env_->num_envs() / env_->num_copies();
  if (agents <= 1) return;
  const std::string k = std::to_string(agents);
  log_->line("note: " + experiment_.env.id + " has " + k +
             " agents sharing one policy: each env step counts as " + k +
             " timesteps (total_timesteps, time/total_timesteps, time/fps, every freq; a rollout "
             "of n_steps is n_steps x " +
             k +
             " samples per env), while ep_len_mean counts env "
             "steps and ep_rew_mean sums the " +
             k + " agents' rewards");
}

void TrainingRun::build_logging() {
  bar_.emplace(experiment_.run.total_timesteps,  // run() renews it
               isatty(STDOUT_FILENO) != 0 && experiment_.run.verbose > 0);
  auto csv_sink = std::make_unique<CsvSink>(outcome_.run_dir + "/progress.csv", resuming_);
  progress_csv_ = csv_sink.get();
  logger_.add_sink(std::move(csv_sink));
  if (experiment_.run.verbose > 0)
    logger_.add_sink(std::make_unique<ConsoleTableSink>(std::cout, experiment_.run.console_interval,
                                                        [this] { bar_->clear(); }));
  logger_.add_sink(std::make_unique<ConsoleTableSink>(log_->table(), 0.0));
  if (!experiment_.run.tensorboard_log.value.empty()) build_tensorboard_log();
  context_.emplace(TrainingContext{
      experiment_.env, experiment_.run.seed, registry_, outcome_.run_dir, *algorithm_, *env_,
      &logger_,
      [this](const std::string& message) {
        bar_->clear();
        log_->line(message);
      },
      [this](const std::string& name) { save_model(name); },
      [this](const std::string& name) { save_checkpoint(name); }, resuming_, on_evaluation_,
      [this] {
        const AlgorithmSetup setup{env_->observation_space(), env_->action_space(),
                                   env_->num_envs(), experiment_.run.seed, execution_.pool};
        return make_algorithm(experiment_, registry_, setup);
      }});
  callbacks_ = make_callbacks(experiment_, *context_);
  last_checkpoint_ = resuming_ ? resume_->path : "";
}

// A new run starts a TensorBoard run; a resumed one continues the one its checkpoint names.
void TrainingRun::build_tensorboard_log() {
  const RunConfig& run = experiment_.run;
  const std::string& dir = run.tensorboard_log.value;
  const std::string name = run.tb_log_name.value_or(run.name);
  const bool continues =
      resuming_ && resume_->checkpoint.training_state.count(std::string(kTrainingStatePrefix) +
                                                            kTensorBoardState + "/run") != 0;
  auto log = std::make_unique<TensorBoardLog>(
      continues ? TensorBoardLog::resume(
                      dir, name, training_state_reader(resume_->checkpoint, kTensorBoardState),
                      [this](const std::string& line) { log_->line(line); })
                : TensorBoardLog::start(dir, name, experiment_.resolved));
  tensorboard_ = log.get();
  logger_.add_sink(std::move(log));
  log_->line("TensorBoard: " + tensorboard_->run_dir() + " (view with: tensorboard --logdir " +
             dir + ")");
}

// The checkpoint's algorithm, env, callback and logger state, checked against this run.
void TrainingRun::restore() {
  const ModelFile& checkpoint = resume_->checkpoint;
  try {
    algorithm_->load(checkpoint.tensors);
    algorithm_->load_training_state(training_state_reader(checkpoint, kAlgoState));
    env_->read_state(training_state_reader(checkpoint, kEnvState));
    read_callback_states(training_state_reader(checkpoint, kCallbackState), callbacks_);
    logger_.restore_pending(read_pending_log(training_state_reader(checkpoint, kLoggerState)));
  } catch (const std::exception& e) {
    throw RuntimeFailure("cannot resume from " + resume_->path + ": " + e.what());
  }
  if (algorithm_->num_timesteps() != checkpoint.meta.num_timesteps)
    throw RuntimeFailure("cannot resume from " + resume_->path + ": its meta.json says step " +
                         std::to_string(checkpoint.meta.num_timesteps) +
                         " but its training state is at step " +
                         std::to_string(algorithm_->num_timesteps()));
}

[[noreturn]] void TrainingRun::stop_diverged(const std::string& problem) {
  // A NaN or inf stops the run, naming the step and the quantity (non_finite_check.hpp).
  std::string message = "training diverged at step " + std::to_string(algorithm_->num_timesteps()) +
                        ": " + problem + ".";
  message += last_checkpoint_.empty()
                 ? " No checkpoint was written (set checkpoint.freq to keep one)."
                 : " The last good checkpoint is " + last_checkpoint_ + ".";
  log_->table() << "error: " << message << "\n";  // main prints it on stderr
  log_->check();
  throw RuntimeFailure(message);
}

// Never write a non-finite model.
TensorMap TrainingRun::finite_model_tensors() {
  TensorMap model;
  algorithm_->save(model);
  const std::string problem = describe_non_finite(model);
  if (!problem.empty()) stop_diverged(problem);
  return model;
}

// Model files carry the normalisation statistics of training env 0 (shared by all envs).
// `name` is a file of the run directory (model.zip, best_model.zip).
void TrainingRun::save_model(const std::string& name) {
  finite_model_tensors();
  TensorMap statistics;
  save_model_statistics(env_->env(0), statistics);
  write_zip_atomic(*dir_, name, model_members(*algorithm_, experiment_, env_->env(0), statistics));
}

// `name`: checkpoints/<name>, a step_<N>.zip.
void TrainingRun::save_checkpoint(const std::string& name) {
  finite_model_tensors();
  TensorMap extra;
  save_model_statistics(env_->env(0), extra);
  if (resumable_) {
    TrainingStateWriter state(extra);
    StateWriter algo = state.part(kAlgoState), env = state.part(kEnvState);
    algorithm_->save_training_state(algo);
    env_->write_state(env);
    write_callback_states(state.part(kCallbackState), callbacks_);
    write_pending_log(state.part(kLoggerState), logger_.pending());
    if (tensorboard_) tensorboard_->write_state(state.part(kTensorBoardState));
    progress_csv_->flush();
    log_->check();
    write_log_marks(state.part(kFileMarks), *dir_, appended_files(experiment_));
  }
  const DirHandle checkpoints = dir_->make_subdir("checkpoints");
  write_zip_atomic(checkpoints, name, model_members(*algorithm_, experiment_, env_->env(0), extra));
  if (resumable_) last_checkpoint_ = checkpoints.child(name);
}

bool TrainingRun::at_safe_point(int64_t num_timesteps) {
  const std::string problem = describe_non_finite(logger_.pending());
  if (!problem.empty()) stop_diverged(problem);
  for (const auto& callback : callbacks_) callback->at_safe_point(num_timesteps);
  for (const auto& callback : *extra_callbacks_) callback->at_safe_point(num_timesteps);
  log_->check();
  if (!interrupt_requested()) return true;
  if (!resumable_) return false;  // nothing to resume from: just stop, model.zip follows
  const std::string name = checkpoint_name(num_timesteps);
  const std::string path = outcome_.run_dir + "/checkpoints/" + name;
  if (last_checkpoint_ != path) save_checkpoint(name);
  outcome_.checkpoint_path = path;
  return false;
}

TrainingHooks TrainingRun::hooks() {
  TrainingHooks hooks;
  hooks.logger = &logger_;
  hooks.log_interval = experiment_.run.log_interval.value_or(0);
  hooks.on_step = [this](int64_t num_timesteps) {
    bar_->update(num_timesteps);
    bool continue_training = true;  // SB3 CallbackList: every callback runs, any can stop
    for (const auto& callback : callbacks_)
      continue_training = callback->on_step(num_timesteps) && continue_training;
    for (const auto& callback : *extra_callbacks_)
      continue_training = callback->on_step(num_timesteps) && continue_training;
    return continue_training && interrupt_count() < 2;
  };
  // Parameters once per log row: cheap next to the updates between rows.
  hooks.on_log = [this](int64_t) { finite_model_tensors(); };
  hooks.at_safe_point = [this](int64_t num_timesteps) { return at_safe_point(num_timesteps); };
  hooks.on_rollout_end = [this](int64_t num_timesteps) {
    for (const auto& callback : callbacks_) callback->on_rollout_end(num_timesteps);
    for (const auto& callback : *extra_callbacks_) callback->on_rollout_end(num_timesteps);
  };
  return hooks;
}

TrainOutcome TrainingRun::run(int64_t total_timesteps,
                              const std::vector<std::unique_ptr<Callback>>& extra) {
  extra_callbacks_ = &extra;
  outcome_.checkpoint_path.clear();
  outcome_.stop_reason.clear();
  bar_.emplace(total_timesteps, isatty(STDOUT_FILENO) != 0 && experiment_.run.verbose > 0);
  TrainingHooks training_hooks = hooks();
  outcome_.start_timesteps = algorithm_->num_timesteps();  // a resumed run's checkpoint step
  const auto start = std::chrono::steady_clock::now();
  std::string stopped_by_others;
  try {
    algorithm_->learn(*env_, total_timesteps, training_hooks);
  } catch (const SeatsStopped& e) {
    // A per-agent run's other learner stopped (Ctrl-C seen a step earlier there, or a failure
    // there): this one cannot step its shared env, and keeps what it has learnt so far.
    stopped_by_others = e.what();
  }
  outcome_.wall_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  outcome_.timesteps = algorithm_->num_timesteps();
  outcome_.interrupted = interrupt_requested() || !stopped_by_others.empty();
  if (!stopped_by_others.empty()) outcome_.stop_reason = stopped_by_others;
  finish();
  extra_callbacks_ = nullptr;
  return outcome_;
}

void TrainingRun::finish() {
  using Callbacks = std::vector<std::unique_ptr<Callback>>;
  for (const Callbacks* list : {static_cast<const Callbacks*>(&callbacks_), extra_callbacks_}) {
    for (const auto& callback : *list) {
      callback->on_training_end(outcome_.timesteps, !outcome_.checkpoint_path.empty());
      if (outcome_.stop_reason.empty()) outcome_.stop_reason = callback->stop_reason();
    }
  }
  bar_->finish();
  logger_.flush();
  if (tensorboard_ && !outcome_.interrupted) {
    std::string curve;
    if (experiment_.run.tensorboard_images) {
      try {  // a picture is no reason to fail a run that has trained
        curve =
            learning_curve_png(outcome_.run_dir, experiment_.algo.id + " on " + experiment_.env.id);
      } catch (const std::exception& e) {
        log_->line(std::string("note: no learning-curve image for TensorBoard: ") + e.what());
      }
    }
    tensorboard_->finish(outcome_.timesteps, true, curve);
  }
  outcome_.model_path = outcome_.run_dir + "/model.zip";
  save_model("model.zip");
  if (!outcome_.stop_reason.empty()) log_->line("stopped early: " + outcome_.stop_reason);
  log_->line(format_session_summary(session_summary(outcome_)) + "; model saved to " +
             outcome_.model_path);
  if (!outcome_.interrupted) {  // the last file written: `rlrun sweep run` skips such runs
    dir_->write_atomic(kFinishedMarker, "timesteps " + std::to_string(outcome_.timesteps) + "\n");
    return;
  }
  if (!outcome_.checkpoint_path.empty())
    log_->line("checkpoint saved to " + outcome_.checkpoint_path +
               "; resume with: rlrun train --resume " + outcome_.run_dir);
  else if (!last_checkpoint_.empty())
    log_->line("stopped without a checkpoint; the last one is " + last_checkpoint_ +
               " (rlrun train --resume " + outcome_.run_dir + " continues from it)");
}

}  // namespace trainer_detail

using trainer_detail::TrainingRun;

TrainOutcome train_experiment(const Experiment& experiment, const Registry& registry,
                              const ExecutionContext& execution,
                              const std::vector<std::string>& resume_from,
                              EvaluationListener on_evaluation) {
  const auto train_one = [](const Experiment& one, const Registry& components,
                            const ExecutionContext& threads, EvaluationListener listener) {
    TrainingRun run(one, components, threads, {}, std::move(listener));
    return run.run(one.run.total_timesteps);
  };
  if (experiment.env.section.agent_policies == "per_agent") {
    if (!resume_from.empty())
      throw UsageError(
          "a per-agent run (env.agent_policies: per_agent) cannot be resumed: its "
          "learners' checkpoints hold their models only");
    return train_per_agent(experiment, registry, execution, std::move(on_evaluation), train_one);
  }
  TrainingRun run(experiment, registry, execution, resume_from, std::move(on_evaluation));
  return run.run(experiment.run.total_timesteps);
}

struct TrainingSession::Impl {
  Impl(Experiment e, const Registry& registry, const ExecutionContext& execution)
      : experiment(std::move(e)), run(experiment, registry, execution, {}, {}) {}
  Experiment experiment;  // before run, which refers to it
  TrainingRun run;
};

TrainingSession::TrainingSession(Experiment experiment, const Registry& registry,
                                 const ExecutionContext& execution) {
  if (experiment.env.section.agent_policies == "per_agent")
    throw UsageError("a per-agent run (env.agent_policies: per_agent) trains with rlrun.train");
  impl_ = std::make_unique<Impl>(std::move(experiment), registry, execution);
}

TrainingSession::~TrainingSession() = default;

TrainOutcome TrainingSession::learn(int64_t total_timesteps,
                                    const std::vector<std::unique_ptr<Callback>>& extra,
                                    std::optional<int> log_interval) {
  if (log_interval) impl_->experiment.run.log_interval = *log_interval;  // the run reads it here
  return impl_->run.run(total_timesteps, extra);
}

TrainingContext& TrainingSession::context() { return impl_->run.context(); }

int64_t TrainingSession::num_timesteps() const { return impl_->run.num_timesteps(); }

const Experiment& TrainingSession::experiment() const { return impl_->experiment; }

}  // namespace rlrun
