// rlrun: train, evaluate and inspect RL agents from YAML experiment files.
// Exit codes (DESIGN.md §6): 0 ok, 2 bad usage or config, 1 runtime failure.
#include <csignal>
#include <iostream>

#include "cli_values.hpp"
#include "commands.hpp"
#include "rlrun/core/errors.hpp"
#include "rlrun/core/fork_join.hpp"

int main(int argc, char** argv) {
  // A file-size limit (ulimit -f) must end in the write error EFBIG, which names the file
  // (core/checked_file.hpp), not in SIGXFSZ killing rlrun with a core dump.
  std::signal(SIGXFSZ, SIG_IGN);
  CLI::App app{"rlrun " RLRUN_VERSION
               ": Stable-Baselines3-style reinforcement learning from YAML experiment files"};
  app.require_subcommand(1);
  app.set_version_flag("--version", RLRUN_VERSION);
  // A global option, accepted before or after the subcommand (fallthrough).
  int threads = 0;
  app.add_option("--threads", threads,
                 "cores per run, 1 or 2 (default: RLRUN_THREADS, else 2 when two CPUs are "
                 "available; use 1 when several runs share the cores). Results are identical.")
      ->transform(rlrun::cli::integer_in(1, 2));
  app.fallthrough();
  rlrun::cli::Action train = rlrun::cli::add_train(app);
  rlrun::cli::Action eval = rlrun::cli::add_eval(app);
  rlrun::cli::Action list = rlrun::cli::add_list(app);
  rlrun::cli::Action check_env = rlrun::cli::add_check_env(app);
  rlrun::cli::Action record = rlrun::cli::add_record(app);
  rlrun::cli::Action sweep = rlrun::cli::add_sweep(app);
  rlrun::cli::Action report = rlrun::cli::add_report(app);
  rlrun::cli::Action plot = rlrun::cli::add_plot(app);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);
    return code == 0 ? rlrun::kExitOk : rlrun::kExitUsage;
  }
  try {
    rlrun::ForkJoin::configure_shared(threads != 0 ? threads : rlrun::ForkJoin::default_threads());
    if (app.got_subcommand("train")) return train();
    if (app.got_subcommand("eval")) return eval();
    if (app.got_subcommand("list")) return list();
    if (app.got_subcommand("check-env")) return check_env();
    if (app.got_subcommand("record")) return record();
    if (app.got_subcommand("sweep")) return sweep();
    if (app.got_subcommand("report")) return report();
    if (app.got_subcommand("plot")) return plot();
  } catch (const rlrun::ConfigError& e) {
    std::cerr << "error: " << e.what() << std::endl;
    return rlrun::kExitUsage;
  } catch (const rlrun::UsageError& e) {
    std::cerr << "error: " << e.what() << std::endl;
    return rlrun::kExitUsage;
  } catch (const rlrun::RuntimeFailure& e) {
    std::cerr << "error: " << e.what() << std::endl;
    return rlrun::kExitRuntime;
  } catch (const std::exception& e) {
    std::cerr << "error: " << e.what() << std::endl;
    return rlrun::kExitRuntime;
  }
  return rlrun::kExitUsage;
}
