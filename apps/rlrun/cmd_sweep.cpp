// rlrun sweep SWEEP.yaml [--out DIR] [--set key=value]...
//                                  expand into <out_dir>/manifest.yaml + configs/
// rlrun sweep run MANIFEST [-j N] [--index I] [--set key=value]... [--plugin LIB]
//                                  train the runs (skip finished, resume interrupted), each
//                                  in a child process whose console output is kept in
//                                  <out_dir>/logs/ (with --index: run I here, output as usual)
// rlrun sweep slurm MANIFEST [--set key=value]... [--plugin LIB]
//                                  write <out_dir>/sweep.sbatch (an array job of `sweep run`)
// rlrun sweep status MANIFEST      each run's state
//
// --set means what it means for `train`: one value for every run. Given when the sweep is
// expanded it goes into the runs' configs (like the sweep file's `set:`); given to `sweep run`
// (or `sweep slurm`, which passes it on) it also vouches for values the untrusted manifest's
// configs carry (docs/security.md). --out belongs to expanding: a manifest's runs train where it
// says.
#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <map>

#include "cli_values.hpp"
#include "commands.hpp"
#include "parallel_runs.hpp"
#include "plugin_option.hpp"
#include "rlrun/core/config_node.hpp"
#include "rlrun/core/errors.hpp"
#include "rlrun/core/interrupt.hpp"
#include "rlrun/core/plural.hpp"
#include "rlrun/runtime/components/builtins.hpp"
#include "rlrun/runtime/experiment/experiment.hpp"
#include "rlrun/runtime/io/run_directory.hpp"
#include "rlrun/runtime/run/resume_point.hpp"
#include "rlrun/runtime/run/trainer.hpp"
#include "rlrun/runtime/workflows/sbatch_script.hpp"
#include "rlrun/runtime/workflows/sweep.hpp"

namespace rlrun::cli {

namespace {

namespace fs = std::filesystem;

// Holds an exclusive lock on <out_dir>/locks/<index>.lock while a run trains, so two `sweep
// run` processes (a Slurm task and a local re-run, say) never train the same run at once.
class SweepSlotLock {
 public:
  SweepSlotLock(const Sweep& sweep, int index) {
    const fs::path dir = fs::path(sweep.manifest).parent_path() / "locks";
    fs::create_directories(dir);
    fd_ = open((dir / (std::to_string(index) + ".lock")).c_str(),
               O_RDWR | O_CREAT | O_CLOEXEC | O_NOFOLLOW, 0644);
    if (fd_ < 0) throw RuntimeFailure("cannot create the lock file in " + dir.string());
    held_ = flock(fd_, LOCK_EX | LOCK_NB) == 0;
  }
  ~SweepSlotLock() {
    if (fd_ >= 0) close(fd_);  // releases the lock
  }
  bool held() const { return held_; }

 private:
  int fd_ = -1;
  bool held_ = false;
};

// Trains run `index` in this process. The last line printed starts with "sweep: " (the
// parent's summary shows it).
// `overrides` are the user's --set values, which vouch for values the untrusted manifest's
// configs carry (docs/security.md); `plugins` are loaded already.
int run_one(const Sweep& sweep, int index, const std::vector<std::string>& overrides,
            Registry& registry, const ExecutionContext& execution) {
  if (index < 0 || index >= static_cast<int>(sweep.runs.size()))
    throw UsageError("--index " + std::to_string(index) + ": the manifest has runs 0-" +
                     std::to_string(sweep.runs.size() - 1));
  const SweepRun& run = sweep.runs[index];
  const std::string name = "run " + std::to_string(index) + " (" + run.id + ")";
  SweepSlotLock lock(sweep, index);
  if (!lock.held()) {
    std::printf("sweep: %s is being trained by another process; left to it\n", name.c_str());
    return 0;
  }
  const RunState state = run_state(run);
  if (state != RunState::kNew && !run_config_matches(run))
    throw UsageError(name + ": " + run.run_dir + " was trained with other settings than " +
                     run.config +
                     " (the sweep file changed after the run started); delete "
                     "that directory to train the run again, or give the sweep another out_dir");
  std::vector<std::string> vouched = overrides;
  for (const std::string& o : sweep_vouched_overrides(sweep, run)) vouched.push_back(o);
  install_interrupt_handlers();
  TrainOutcome outcome;
  switch (state) {
    case RunState::kFinished:
      std::printf("sweep: %s finished before; skipped\n", name.c_str());
      return 0;
    case RunState::kResumable: {
      const std::vector<std::string> checkpoints = resume_candidates(run.run_dir);
      std::printf("sweep: %s resuming from %s\n", name.c_str(), checkpoints.front().c_str());
      std::fflush(stdout);
      const Experiment experiment =
          load_experiment(run.run_dir + "/config.yaml", vouched, registry, ConfigTrust::kUntrusted);
      outcome = train_experiment(experiment, registry, execution, checkpoints);
      break;
    }
    case RunState::kPartial:
      // Started, but stopped before its first checkpoint: nothing to keep.
      std::printf("sweep: %s left no checkpoint; starting it again\n", name.c_str());
      fs::remove_all(run.run_dir);
      [[fallthrough]];
    case RunState::kNew: {
      std::fflush(stdout);
      const Experiment experiment =
          load_experiment(run.config, vouched, registry, ConfigTrust::kUntrusted);
      const fs::path target = fs::absolute(fs::path(experiment.run.out_dir) / experiment.run.name /
                                           ("seed" + std::to_string(experiment.run.seed)))
                                  .lexically_normal();
      if (target != fs::path(run.run_dir))
        throw UsageError(name + ": its config " + run.config + " trains into " + target.string() +
                         ", not the manifest's " + run.run_dir);
      outcome = train_experiment(experiment, registry, execution);
      if (fs::absolute(outcome.run_dir).lexically_normal() != fs::path(run.run_dir))
        throw RuntimeFailure("run " + run.id + " trained into " + outcome.run_dir + " instead of " +
                             run.run_dir);
      break;
    }
  }
  std::printf("sweep: %s %s\n", name.c_str(),
              format_session_summary(session_summary(outcome)).c_str());
  return outcome.interrupted ? 130 : 0;
}

struct SweepCliOptions {
  std::string sweep_file, manifest;
  int jobs = 1;
  int index = -1;
  std::vector<std::string> overrides, plugins;  // `sweep run`'s and `sweep slurm`'s
  std::string out;                              // expanding a sweep file only
  std::vector<std::string> expand_overrides;    // expanding a sweep file only
};

// `sweep run`'s --set and --plugin as arguments for the `sweep run --index I` it starts per run.
std::vector<std::string> passed_on(const SweepCliOptions& o) {
  std::vector<std::string> args;
  for (const std::string& v : o.overrides) args.insert(args.end(), {"--set", v});
  for (const std::string& p : o.plugins) args.insert(args.end(), {"--plugin", p});
  return args;
}

int run_all(const Sweep& sweep, int jobs, const std::vector<std::string>& passed_on,
            const ExecutionContext& execution) {
  std::map<RunState, int> before;
  std::vector<ChildRun> children;
  for (const SweepRun& run : sweep.runs) {
    const RunState state = run_state(run);
    ++before[state];
    if (state == RunState::kFinished) continue;
    // Runs at once share this process's threads.
    const std::string threads = std::to_string(threads_per_job(execution, jobs));
    std::vector<std::string> args{
        "--threads", threads, "sweep", "run", sweep.manifest, "--index", std::to_string(run.index)};
    args.insert(args.end(), passed_on.begin(), passed_on.end());
    children.push_back({run.id, args, run_console_log(sweep, run)});
  }
  std::printf(
      "sweep %s: %s: %d finished before (skipped), %d to resume, %d to start "
      "(%d again, having left no checkpoint)\n",
      sweep.name.c_str(), count_of(static_cast<int64_t>(sweep.runs.size()), "run").c_str(),
      before[RunState::kFinished], before[RunState::kResumable],
      before[RunState::kNew] + before[RunState::kPartial], before[RunState::kPartial]);
  int code = 0;
  const std::string logs = "console output of each in " +
                           (fs::path(sweep.manifest).parent_path() / "logs").string() +
                           "/<run id>.txt";
  if (!children.empty()) code = run_in_parallel(children, std::max(jobs, 1), "run", logs);
  int finished = 0;
  for (const SweepRun& run : sweep.runs) finished += run_state(run) == RunState::kFinished;
  std::printf("sweep %s: %d of %s finished\n", sweep.name.c_str(), finished,
              count_of(static_cast<int64_t>(sweep.runs.size()), "run").c_str());
  if (code == 0 && finished < static_cast<int>(sweep.runs.size())) code = 1;  // e.g. left to others
  return code;
}

}  // namespace

Action add_sweep(CLI::App& app, Registry& registry, const ExecutionContext& execution) {
  auto options = std::make_shared<SweepCliOptions>();
  CLI::App* sub = app.add_subcommand(
      "sweep", "expand a sweep file (base config x overrides x seeds) into a manifest of runs");
  sub->add_option("sweep_file", options->sweep_file, "the sweep file (see docs/sweeps.md)");
  CLI::Option* out_option = sub->add_option(
      "--out", options->out, "the sweep's out_dir (manifest.yaml, configs/, runs/, logs/)");
  CLI::Option* expand_set_option =
      sub->add_option("--set", options->expand_overrides,
                      "override a config value in every run, like the sweep file's set: (and "
                      "over it), e.g. --set run.total_timesteps=20000 (repeatable)")
          ->allow_extra_args(false);
  const auto add_run_options = [&options](CLI::App* command, const std::string& what) {
    command
        ->add_option("--set", options->overrides,
                     "override a value in every run's config " + what +
                         " (a manifest is untrusted: this is how you vouch for a program or "
                         "scenario file it names; docs/security.md; repeatable)")
        ->allow_extra_args(false);
    add_plugin_option(command, options->plugins);
  };
  CLI::App* run = sub->add_subcommand(
      "run", "train a manifest's runs: finished ones are skipped, interrupted ones resumed");
  run->add_option("manifest", options->manifest, "manifest.yaml written by `rlrun sweep`")
      ->required();
  run->add_option("-j,--jobs", options->jobs, "runs at once (sharing --threads equally)")
      ->transform(integer_in(1));
  run->add_option("--index", options->index, "train only run I (what a Slurm array task does)")
      ->transform(integer_in(0));
  add_run_options(run, "as it trains");
  CLI::App* slurm = sub->add_subcommand("slurm", "write an sbatch --array script for a manifest");
  slurm->add_option("manifest", options->manifest, "manifest.yaml")->required();
  add_run_options(slurm, "(passed on to each array task's `sweep run`)");
  CLI::App* status = sub->add_subcommand("status", "print each run's state");
  status->add_option("manifest", options->manifest, "manifest.yaml")->required();
  return [options, run, slurm, status, out_option, expand_set_option, &registry, &execution]() {
    // CLI11 lets a subcommand's unknown option fall through to `sweep`'s own: refuse those that
    // belong to expanding a sweep file rather than take them silently.
    if (run->parsed() || slurm->parsed() || status->parsed()) {
      const std::string command = run->parsed() ? "run" : slurm->parsed() ? "slurm" : "status";
      if (!options->sweep_file.empty())  // a word before the subcommand, or a stray one after it
        throw UsageError("rlrun sweep " + command + ": unexpected argument '" +
                         options->sweep_file + "' (rlrun sweep " + command +
                         " --help lists its options)");
      if (out_option->count() > 0)
        throw UsageError("sweep " + command +
                         " takes no --out: a manifest's runs train where it "
                         "says; expand the sweep file again with --out (rlrun sweep SWEEP.yaml "
                         "--out DIR) for another place");
      if (expand_set_option->count() > 0)
        throw UsageError(command == "status" ? std::string("sweep status takes no --set")
                                             : "--set before `" + command +
                                                   "` is for expanding a sweep file; "
                                                   "give it after the manifest: rlrun sweep " +
                                                   command + " MANIFEST --set key=value");
    }
    if (run->parsed()) {
      load_plugin_options(options->plugins, registry);
      const Sweep sweep = read_manifest(options->manifest);
      if (options->index >= 0)
        return run_one(sweep, options->index, options->overrides, registry, execution);
      return run_all(sweep, options->jobs, passed_on(*options), execution);
    }
    if (slurm->parsed()) {
      const Sweep sweep = read_manifest(options->manifest);
      const fs::path dir = fs::path(sweep.manifest).parent_path();
      fs::create_directories(dir / "slurm");
      const std::string script = (dir / "sweep.sbatch").string();
      write_text_atomic(script, slurm_script(sweep, own_binary(), passed_on(*options)));
      std::printf("wrote %s (%s); submit it with: sbatch %s\n", script.c_str(),
                  count_of(static_cast<int64_t>(sweep.runs.size()), "array task").c_str(),
                  shell_quote(script).c_str());
      return 0;
    }
    if (status->parsed()) {
      const Sweep sweep = read_manifest(options->manifest);
      for (const SweepRun& r : sweep.runs)
        std::printf("%3d  %-10s %s  %s%s\n", r.index, to_string(run_state(r)), r.id.c_str(),
                    r.run_dir.c_str(),
                    run_config_matches(r) ? "" : "  (settings changed since it ran)");
      return 0;
    }
    if (options->sweep_file.empty())
      throw UsageError(
          "sweep needs a sweep file (rlrun sweep configs/sweeps/x.yaml) or one of "
          "run, slurm, status with a manifest");
    std::error_code ec;
    if (!fs::exists(options->sweep_file, ec)) {  // `rlrun sweep rnu m.yaml`: a mistyped command
      const std::string meant = closest_name(options->sweep_file, {"run", "slurm", "status"});
      if (!meant.empty())
        throw UsageError("'" + options->sweep_file +
                         "' is neither a sweep file nor a sweep "
                         "command; did you mean 'rlrun sweep " +
                         meant + "'?");
    }
    const Sweep sweep =
        expand_sweep(options->sweep_file, registry, {options->out, options->expand_overrides});
    std::printf("sweep %s: %s -> %s\n", sweep.name.c_str(),
                count_of(static_cast<int64_t>(sweep.runs.size()), "run").c_str(),
                sweep.manifest.c_str());
    for (const SweepRun& r : sweep.runs) std::printf("  %3d  %s\n", r.index, r.id.c_str());
    const std::string manifest =
        shell_quote(sweep.manifest);  // the commands as one would type them
    std::printf("train them: rlrun sweep run %s -j 2\n  or on Slurm: rlrun sweep slurm %s\n",
                manifest.c_str(), manifest.c_str());
    return 0;
  };
}

}  // namespace rlrun::cli
