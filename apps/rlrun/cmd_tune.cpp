// rlrun tune STUDY.yaml [-j N] [--n-trials N] [--n-timesteps N] [--out DIR] [--set key=value]...
//                      [--plugin LIB]...
//                                  run the study's trials (docs/tune.md): N worker processes
//                                  share the study journal; a study resumes where it stopped
// rlrun tune STUDY.yaml --slurm [--workers N]
//                                  write <out_dir>/tune.sbatch: an array of N workers
// rlrun tune report STUDY [--top K] [--plot FILE] [--best-config FILE] [--trial N]
//                                  the study's best trials, parameter importances and history
//                                  plot; the best trial as an experiment file; re-train a trial
//
// STUDY for `report` is the study file, or a journal (then --study-name when it holds several
// studies; --best-config and --trial need the study file, which names the base experiment).
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>

#include "cli_values.hpp"
#include "commands.hpp"
#include "parallel_runs.hpp"
#include "plugin_option.hpp"
#include "rlrun/core/errors.hpp"
#include "rlrun/core/interrupt.hpp"
#include "rlrun/core/plural.hpp"
#include "rlrun/runtime/experiment/experiment.hpp"
#include "rlrun/runtime/io/run_directory.hpp"
#include "rlrun/runtime/run/trainer.hpp"
#include "rlrun/runtime/workflows/sbatch_script.hpp"
#include "rlrun/tune/journal_storage.hpp"
#include "rlrun/tune/study_config.hpp"
#include "rlrun/tune/study_report.hpp"
#include "rlrun/tune/tune_worker.hpp"

namespace rlrun::cli {

namespace {

namespace fs = std::filesystem;
using tune::FrozenTrial;
using tune::StudyConfig;
using tune::TrialState;

struct TuneOptions {
  std::string study_file;
  int jobs = 1;
  std::optional<int> n_trials;
  std::optional<int64_t> n_timesteps;
  std::string out;
  std::vector<std::string> set, plugins;
  bool slurm = false;
  bool verbose = false;
  int workers = 2;
  // report
  std::string study;
  std::string study_name;
  int top = 10;
  std::string plot, best_config;
  std::optional<int> trial;
};

// The options each worker process gets from this one.
std::vector<std::string> passed_on(const TuneOptions& o) {
  std::vector<std::string> args;
  for (const std::string& v : o.set) args.insert(args.end(), {"--set", v});
  for (const std::string& p : o.plugins) args.insert(args.end(), {"--plugin", p});
  if (o.n_trials) args.insert(args.end(), {"--n-trials", std::to_string(*o.n_trials)});
  if (o.n_timesteps) args.insert(args.end(), {"--n-timesteps", std::to_string(*o.n_timesteps)});
  if (!o.out.empty()) args.insert(args.end(), {"--out", fs::absolute(o.out).string()});
  if (o.verbose) args.push_back("--verbose");
  return args;
}

// The state of the study after workers ran: counts and the best trial.
void print_study_summary(const StudyConfig& study) {
  tune::JournalStorage storage(study.storage);
  const auto id = storage.state().find_study(study.name);
  if (!id) return;
  const std::vector<FrozenTrial> trials = storage.state().trials(*id);
  int complete = 0, pruned = 0, failed = 0, other = 0;
  for (const FrozenTrial& t : trials) {
    if (t.state == TrialState::kComplete)
      ++complete;
    else if (t.state == TrialState::kPruned)
      ++pruned;
    else if (t.state == TrialState::kFail)
      ++failed;
    else
      ++other;
  }
  const FrozenTrial* best = tune::best_trial(
      trials, study.maximize() ? tune::StudyDirection::kMaximize : tune::StudyDirection::kMinimize);
  std::printf(
      "study %s (%s): %d complete, %d pruned, %d failed, %d running or waiting; %d of "
      "%d trials counted\n",
      study.name.c_str(), study.storage.c_str(), complete, pruned, failed, other,
      tune::counted_trials(trials), study.n_trials);
  if (best) {
    std::printf("best: trial %d, value %.6g:", best->number, *best->value());
    for (const auto& [name, internal] : best->params)
      std::printf(" %s=%s", name.c_str(), best->param(name).dump().c_str());
    std::printf("\n");
  }
  std::printf("report: rlrun tune report %s\n", shell_quote(study.source).c_str());
}

int run_study(const TuneOptions& o, Registry& registry, const ExecutionContext& execution) {
  load_plugin_options(o.plugins, registry);
  StudyConfig study = tune::load_study(o.study_file, registry, o.set, o.out, o.n_timesteps);
  if (o.n_trials) study.n_trials = *o.n_trials;
  fs::create_directories(study.out_dir);
  if (o.slurm) {
    SlurmArrayJob job;
    job.name = "tune-" + study.name;
    job.script = (fs::path(study.out_dir) / "tune.sbatch").string();
    job.output_dir = (fs::path(study.out_dir) / "slurm").string();
    job.tasks = o.workers;
    job.options = study.slurm;
    job.comment = {"Written by: rlrun tune " + shell_quote(study.source) + " --slurm",
                   "Each array task is one worker of study " + study.name + " (" + study.storage +
                       "); together they run " + std::to_string(study.n_trials) + " trials."};
    job.command = shell_quote(own_binary()) + " --threads " +
                  std::to_string(study.slurm.cpus_per_task) + " tune " + shell_quote(study.source);
    for (const std::string& arg : passed_on(o)) {
      if (!script_path_problem(arg).empty())
        throw UsageError("cannot write the sbatch script: a control character in " + arg);
      job.command += ' ';
      job.command += shell_quote(arg);
    }
    fs::create_directories(job.output_dir);
    write_text_atomic(job.script, slurm_array_script(job));
    std::printf("wrote %s (%s); submit it with: sbatch %s\n", job.script.c_str(),
                count_of(o.workers, "worker").c_str(), shell_quote(job.script).c_str());
    return 0;
  }
  std::printf(
      "study %s: %s, %d trials of %s x %lld steps, objective %s (%s), sampler %s, pruner "
      "%s, journal %s\n",
      study.name.c_str(), study.space->describe().c_str(), study.n_trials,
      count_of(study.seeds_per_trial, "seed").c_str(), static_cast<long long>(study.n_timesteps),
      study.objective.metric.c_str(), study.objective.direction.c_str(), study.sampler.type.c_str(),
      study.pruner.type.c_str(), study.storage.c_str());
  std::fflush(stdout);
  int code = 0;
  if (o.jobs > 1) {
    std::vector<ChildRun> workers;
    const fs::path logs = fs::path(study.out_dir) / "logs";
    fs::create_directories(logs);
    for (int w = 0; w < o.jobs; ++w) {
      std::vector<std::string> args{"--threads", std::to_string(threads_per_job(execution, o.jobs)),
                                    "tune", study.source};
      const auto more = passed_on(o);
      args.insert(args.end(), more.begin(), more.end());
      workers.push_back({"worker " + std::to_string(w), args,
                         (logs / ("worker_" + std::to_string(w) + ".txt")).string()});
    }
    code = run_in_parallel(workers, o.jobs, "worker", logs.string() + "/worker_<i>.txt");
  } else {
    const tune::WorkerSummary summary = tune::run_worker(study, registry, execution, o.verbose);
    std::printf("this worker: %d complete, %d pruned, %d failed%s\n", summary.complete,
                summary.pruned, summary.failed,
                summary.interrupted ? "; interrupted (the running trial was re-queued: run the "
                                      "same command to go on)"
                                    : "");
    if (summary.interrupted) code = 130;
  }
  print_study_summary(study);
  return code;
}

int report(const TuneOptions& o, Registry& registry, const ExecutionContext& execution) {
  // A study file (YAML) names the journal; anything else is read as a journal.
  std::optional<StudyConfig> study;
  std::string journal = o.study, name = o.study_name;
  const std::string ext = fs::path(o.study).extension().string();
  if (ext == ".yaml" || ext == ".yml") {
    study = tune::load_study(o.study, registry, {}, o.out, o.n_timesteps);
    journal = study->storage;
    if (name.empty()) name = study->name;
  }
  if (!fs::exists(journal)) throw UsageError(journal + " does not exist (no trial has run yet?)");
  tune::JournalStorage storage(journal);
  if (name.empty()) {
    const std::vector<std::string> names = storage.state().study_names();
    if (names.empty()) throw UsageError(journal + " holds no study");
    if (names.size() > 1)
      throw UsageError(journal + " holds " + std::to_string(names.size()) +
                       " studies: name one with --study-name (" + names.front() + ", ...)");
    name = names.front();
  }
  const auto id = storage.state().find_study(name);
  if (!id) throw UsageError(journal + " holds no study named '" + name + "'");
  const auto& record = storage.state().study(*id);
  const tune::StudyDirection direction = record.directions.at(0);
  const std::vector<FrozenTrial> trials = storage.state().trials(*id);
  tune::ReportOptions options;
  options.top = o.top;
  options.plot_path = o.plot;
  tune::print_study_report(name, direction, trials, options, std::cout);

  if (!o.best_config.empty() || o.trial) {
    if (!study)
      throw UsageError(
          "--best-config and --trial need the study file (it names the base experiment)");
    const FrozenTrial* chosen = nullptr;
    if (o.trial) {
      for (const FrozenTrial& t : trials)
        if (t.number == *o.trial) chosen = &t;
      if (!chosen) throw UsageError("the study has no trial " + std::to_string(*o.trial));
    } else {
      chosen = tune::best_trial(trials, direction);
      if (!chosen) throw UsageError("the study has no complete trial yet");
    }
    const nlohmann::json params = chosen->external_params();
    std::vector<std::string> overrides;
    for (const auto& s : study->set) overrides.push_back(s.assignment());
    for (const auto& p : study->space->overrides_for(params)) overrides.push_back(p.assignment());
    overrides.push_back("run.total_timesteps=" + std::to_string(study->n_timesteps));
    if (!o.best_config.empty()) {
      overrides.push_back("run.name=" + fs::path(o.best_config).stem().string());
      const Experiment experiment = load_experiment(study->base, overrides, registry);
      std::string header = "# Trial " + std::to_string(chosen->number) + " of study " + name +
                           " (" + study->source + ")";
      if (chosen->value())
        header += ": " + study->objective.metric + " = " + std::to_string(*chosen->value());
      header += "\n# written by rlrun tune report --best-config; the trial's parameters:\n";
      for (const auto& [pname, value] : params.items())
        header += "#   " + pname + ": " + value.dump() + "\n";
      write_text_atomic(o.best_config, header + dump_yaml(experiment.resolved));
      std::printf("wrote %s (trial %d); train it with: rlrun train %s\n", o.best_config.c_str(),
                  chosen->number, shell_quote(o.best_config).c_str());
    }
    if (o.trial) {
      install_interrupt_handlers();
      for (int s = 0; s < study->seeds_per_trial; ++s) {
        std::vector<std::string> seed_overrides = overrides;
        seed_overrides.push_back("run.seed=" +
                                 std::to_string(study->base_seed + static_cast<uint64_t>(s)));
        seed_overrides.push_back("run.out_dir=" +
                                 (fs::path(study->out_dir) / "retrained").string());
        seed_overrides.push_back("run.name=trial_" + std::to_string(chosen->number));
        const Experiment experiment = load_experiment(study->base, seed_overrides, registry);
        const TrainOutcome outcome = train_experiment(experiment, registry, execution);
        std::printf("trial %d seed %llu: %s (%s)\n", chosen->number,
                    static_cast<unsigned long long>(experiment.run.seed),
                    format_session_summary(session_summary(outcome)).c_str(),
                    outcome.run_dir.c_str());
        if (outcome.interrupted) return 130;
      }
    }
  }
  return 0;
}

}  // namespace

Action add_tune(CLI::App& app, Registry& registry, const ExecutionContext& execution) {
  auto o = std::make_shared<TuneOptions>();
  CLI::App* sub = app.add_subcommand(
      "tune", "hyperparameter search (TPE, pruning) into an Optuna study journal (docs/tune.md)");
  sub->add_option("study_file", o->study_file, "the study file (docs/tune.md)");
  sub->add_option("-j,--jobs", o->jobs, "worker processes sharing the study (each --threads 1)")
      ->transform(integer_in(1, 256));
  sub->add_option("--n-trials", o->n_trials, "trials in total (instead of the file's n_trials)")
      ->transform(integer_in(1, 1000000));
  sub->add_option("--n-timesteps", o->n_timesteps,
                  "env steps per seed of every trial (instead of the file's n_timesteps)")
      ->transform(integer_in(1, 1'000'000'000'000'000));
  sub->add_option("--out", o->out,
                  "the study's out_dir (its journal, trials/, logs/) instead of the file's");
  sub->add_option("--set", o->set, "override a value of every trial's experiment (repeatable)")
      ->allow_extra_args(false);
  add_plugin_option(sub, o->plugins);
  sub->add_flag("--verbose", o->verbose, "show each trial's training output (its log.txt has it)");
  sub->add_flag("--slurm", o->slurm, "write an sbatch array script of --workers workers instead");
  sub->add_option("--workers", o->workers, "with --slurm: array tasks (workers)")
      ->transform(integer_in(1, 10000));
  CLI::App* rep =
      sub->add_subcommand("report", "a study's best trials, importances and history plot");
  rep->add_option("study", o->study, "the study file or its journal")->required();
  rep->add_option("--study-name", o->study_name, "with a journal of several studies: which one");
  rep->add_option("--out", o->out, "the study's out_dir, when it ran with tune --out");
  rep->add_option("--n-timesteps", o->n_timesteps,
                  "the steps per seed, when it ran with tune --n-timesteps (for --best-config and "
                  "--trial)")
      ->transform(integer_in(1, 1'000'000'000'000'000));
  rep->add_option("--top", o->top, "best trials listed")->transform(integer_in(1, 100000));
  rep->add_option("--plot", o->plot, "write the optimisation history plot (.png or .svg)");
  rep->add_option("--best-config", o->best_config, "write the best trial as an experiment file");
  rep->add_option("--trial", o->trial, "re-train trial N (all its seeds) into <out_dir>/retrained/")
      ->transform(integer_in(0));
  return [o, rep, &registry, &execution]() {
    if (rep->parsed()) {
      if (!o->study_file.empty())
        throw UsageError("rlrun tune report: unexpected argument '" + o->study_file + "'");
      return report(*o, registry, execution);
    }
    if (o->study_file.empty())
      throw UsageError(
          "tune needs a study file (rlrun tune configs/tune/cartpole_ppo.yaml), or "
          "report with a study");
    if (!fs::exists(o->study_file) && o->study_file.size() < 12) {
      const std::string meant = closest_name(o->study_file, {"report"});
      if (!meant.empty())
        throw UsageError("'" + o->study_file +
                         "' is neither a study file nor a tune command; did "
                         "you mean 'rlrun tune " +
                         meant + "'?");
    }
    return run_study(*o, registry, execution);
  };
}

}  // namespace rlrun::cli
