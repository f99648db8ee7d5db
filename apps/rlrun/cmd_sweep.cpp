// rlrun sweep SWEEP.yaml                       expand into <out_dir>/manifest.yaml + configs/
// rlrun sweep run MANIFEST [-j N] [--index I]   train the runs (skip finished, resume interrupted)
// rlrun sweep slurm MANIFEST                    write <out_dir>/sweep.sbatch (an array job)
// rlrun sweep status MANIFEST                   each run's state
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
#include "rlrun/core/errors.hpp"
#include "rlrun/core/fork_join.hpp"
#include "rlrun/runtime/builtins.hpp"
#include "rlrun/runtime/experiment.hpp"
#include "rlrun/runtime/run_directory.hpp"
#include "rlrun/runtime/sbatch_script.hpp"
#include "rlrun/runtime/sweep.hpp"
#include "rlrun/core/interrupt.hpp"
#include "rlrun/runtime/resume_point.hpp"
#include "rlrun/runtime/trainer.hpp"

namespace rlrun::cli {

namespace {

namespace fs = std::filesystem;

std::string own_binary() {
  std::error_code ec;
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  return ec ? "rlrun" : exe.string();
}

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
            Registry& registry) {
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
                     run.config + " (the sweep file changed after the run started); delete "
                     "that directory to train the run again, or give the sweep another out_dir");
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
      const Experiment experiment = load_experiment(run.run_dir + "/config.yaml", overrides,
                                                    registry, ConfigTrust::kUntrusted);
      outcome = train_experiment(experiment, registry, checkpoints);
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
          load_experiment(run.config, overrides, registry, ConfigTrust::kUntrusted);
      const fs::path target = fs::absolute(fs::path(experiment.run.out_dir) / experiment.run.name /
                                           ("seed" + std::to_string(experiment.run.seed)))
                                  .lexically_normal();
      if (target != fs::path(run.run_dir))
        throw UsageError(name + ": its config " + run.config + " trains into " + target.string() +
                         ", not the manifest's " + run.run_dir);
      outcome = train_experiment(experiment, registry);
      if (fs::absolute(outcome.run_dir).lexically_normal() != fs::path(run.run_dir))
        throw RuntimeFailure("run " + run.id + " trained into " + outcome.run_dir +
                             " instead of " + run.run_dir);
      break;
    }
  }
  std::printf("sweep: %s %s\n", name.c_str(),
              format_session_summary(session_summary(outcome)).c_str());
  return outcome.interrupted ? 130 : 0;
}

int run_all(const Sweep& sweep, int jobs, const std::vector<std::string>& passed_on) {
  std::map<RunState, int> before;
  std::vector<ChildRun> children;
  for (const SweepRun& run : sweep.runs) {
    const RunState state = run_state(run);
    ++before[state];
    if (state == RunState::kFinished) continue;
    // One core per run when several share the machine; else this process's own setting.
    const char* threads = jobs > 1 ? "1" : (ForkJoin::shared().enabled() ? "2" : "1");
    std::vector<std::string> args{"--threads", threads, "sweep", "run", sweep.manifest,
                                  "--index", std::to_string(run.index)};
    args.insert(args.end(), passed_on.begin(), passed_on.end());
    children.push_back({run.id, args});
  }
  std::printf("sweep %s: %zu runs: %d finished before (skipped), %d to resume, %d to start "
              "(%d again, having left no checkpoint)\n",
              sweep.name.c_str(), sweep.runs.size(), before[RunState::kFinished],
              before[RunState::kResumable], before[RunState::kNew] + before[RunState::kPartial],
              before[RunState::kPartial]);
  int code = 0;
  if (!children.empty()) code = run_in_parallel(children, std::max(jobs, 1), "runs");
  int finished = 0;
  for (const SweepRun& run : sweep.runs) finished += run_state(run) == RunState::kFinished;
  std::printf("sweep %s: %d of %zu runs finished\n", sweep.name.c_str(), finished, sweep.runs.size());
  if (code == 0 && finished < static_cast<int>(sweep.runs.size())) code = 1;  // e.g. left to others
  return code;
}

}  // namespace

Action add_sweep(CLI::App& app, Registry& registry) {
  struct Options {
    std::string sweep_file, manifest;
    int jobs = 1;
    int index = -1;
    std::vector<std::string> overrides, plugins;
  };
  auto options = std::make_shared<Options>();
  CLI::App* sub = app.add_subcommand(
      "sweep", "expand a sweep file (base config x overrides x seeds) into a manifest of runs");
  sub->add_option("sweep_file", options->sweep_file, "the sweep file (see docs/sweeps.md)");
  CLI::App* run = sub->add_subcommand(
      "run", "train a manifest's runs: finished ones are skipped, interrupted ones resumed");
  run->add_option("manifest", options->manifest, "manifest.yaml written by `rlrun sweep`")->required();
  run->add_option("-j,--jobs", options->jobs, "runs at once (each with --threads 1)")
      ->transform(integer_in(1));
  run->add_option("--index", options->index, "train only run I (what a Slurm array task does)")
      ->transform(integer_in(0));
  run->add_option("--set", options->overrides,
                  "override a value in every run's config (a manifest is untrusted: this is how "
                  "you vouch for a program or scenario file it names; docs/security.md)")
      ->allow_extra_args(false);
  add_plugin_option(run, options->plugins);
  CLI::App* slurm = sub->add_subcommand("slurm", "write an sbatch --array script for a manifest");
  slurm->add_option("manifest", options->manifest, "manifest.yaml")->required();
  CLI::App* status = sub->add_subcommand("status", "print each run's state");
  status->add_option("manifest", options->manifest, "manifest.yaml")->required();
  return [options, run, slurm, status, &registry]() {
    if (run->parsed()) {
      load_plugin_options(options->plugins, registry);
      const Sweep sweep = read_manifest(options->manifest);
      if (options->index >= 0) return run_one(sweep, options->index, options->overrides, registry);
      std::vector<std::string> passed_on;
      for (const std::string& o : options->overrides) passed_on.insert(passed_on.end(), {"--set", o});
      for (const std::string& p : options->plugins) passed_on.insert(passed_on.end(), {"--plugin", p});
      return run_all(sweep, options->jobs, passed_on);
    }
    if (slurm->parsed()) {
      const Sweep sweep = read_manifest(options->manifest);
      const fs::path dir = fs::path(sweep.manifest).parent_path();
      fs::create_directories(dir / "slurm");
      const std::string script = (dir / "sweep.sbatch").string();
      write_text_atomic(script, slurm_script(sweep, own_binary()));
      std::printf("wrote %s (%zu array tasks); submit it with: sbatch %s\n", script.c_str(),
                  sweep.runs.size(), shell_quote(script).c_str());
      return 0;
    }
    if (status->parsed()) {
      const Sweep sweep = read_manifest(options->manifest);
      for (const SweepRun& r : sweep.runs)
        std::printf("%3d  %-10s %s  %s%s\n", r.index, to_string(run_state(r)), r.id.c_str(),
                    r.run_dir.c_str(), run_config_matches(r) ? "" : "  (settings changed since it ran)");
      return 0;
    }
    if (options->sweep_file.empty())
      throw UsageError("sweep needs a sweep file (rlrun sweep configs/sweeps/x.yaml) or one of "
                       "run, slurm, status with a manifest");
    const Sweep sweep = expand_sweep(options->sweep_file, registry);
    std::printf("sweep %s: %zu runs -> %s\n", sweep.name.c_str(), sweep.runs.size(),
                sweep.manifest.c_str());
    for (const SweepRun& r : sweep.runs) std::printf("  %3d  %s\n", r.index, r.id.c_str());
    const std::string manifest = shell_quote(sweep.manifest);  // the commands as one would type them
    std::printf("train them: rlrun sweep run %s -j 2\n  or on Slurm: rlrun sweep slurm %s\n",
                manifest.c_str(), manifest.c_str());
    return 0;
  };
}

}  // namespace rlrun::cli
