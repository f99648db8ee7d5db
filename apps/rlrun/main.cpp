// rlrun: train, evaluate and inspect RL agents from YAML experiment files.
// Exit codes (docs/commands.md): 0 ok, 2 bad usage or config, 1 runtime failure, 128 + signal
// (130: Ctrl-C) when interrupted where no safe point could be waited for (core/errors.hpp).
#include <algorithm>
#include <csignal>
#include <iostream>
#include <new>
#include <optional>
#include <string>

#include "cli_values.hpp"
#include "commands.hpp"
#include "parse_errors.hpp"
#include "process_environment.hpp"
#include "rlrun/core/errors.hpp"
#include "rlrun/core/execution_context.hpp"
#include "rlrun/core/interrupt.hpp"
#include "rlrun/nn/dense_kernels.hpp"
#include "rlrun/runtime/components/builtins.hpp"
#include "thread_count.hpp"

namespace {

// One "error: " line per problem (a config may report several at once).
void print_error(const std::string& message) {
  std::string::size_type start = 0;
  while (start <= message.size()) {
    const auto end = std::min(message.find('\n', start), message.size());
    if (end > start || start == 0)
      std::cerr << "error: " << message.substr(start, end - start) << '\n';
    start = end + 1;
  }
  std::cerr.flush();
}

}  // namespace

int main(int argc, char** argv) {
  // A file-size limit (ulimit -f) must end in the write error EFBIG, which names the file
  // (core/checked_file.hpp), not in SIGXFSZ killing rlrun with a core dump.
  std::signal(SIGXFSZ, SIG_IGN);
  // Ctrl-C and `kill -INT` stop rlrun in every phase, also when it was started with SIGINT
  // ignored (a shell's background job); commands that can stop cleanly install their handlers
  // (core/interrupt.hpp).
  rlrun::use_default_interrupt_actions();
  CLI::App app{"rlrun " RLRUN_VERSION
               ": Stable-Baselines3-style reinforcement learning from YAML experiment files"};
  app.require_subcommand(1);
  // The version and which network kernels this CPU runs (nn/dense_kernels.hpp).
  const std::string version = std::string(RLRUN_VERSION) + " (network kernels: " +
                              rlrun::dense::kernel_path_name(rlrun::dense::best_kernel_path()) +
                              "; RLRUN_KERNELS=avx512|avx2|baseline forces one)";
  app.set_version_flag("--version", version);
  // A global option, accepted before or after the subcommand (fallthrough).
  std::string threads;
  app.add_option("--threads", threads,
                 "threads per run: N, or auto = the CPUs this process may use (affinity mask "
                 "and cgroup quota). Default: RLRUN_THREADS, else auto; use 1 when several runs "
                 "share the cores. Results are identical for any count.")
      ->type_name("N|auto");
  app.fallthrough();
  // Made once the options are read (the thread count), used by the commands' actions.
  std::optional<rlrun::ThreadPool> pool;
  rlrun::ExecutionContext execution;
  // The registry is built here and passed down; --plugin adds to it (runtime/components/builtins.hpp).
  rlrun::Registry registry = rlrun::make_builtin_registry();
  rlrun::cli::Action train = rlrun::cli::add_train(app, registry, execution);
  rlrun::cli::Action eval = rlrun::cli::add_eval(app, registry);
  rlrun::cli::Action list = rlrun::cli::add_list(app, registry);
  rlrun::cli::Action check_env = rlrun::cli::add_check_env(app, registry);
  rlrun::cli::Action record = rlrun::cli::add_record(app, registry);
  rlrun::cli::Action sweep = rlrun::cli::add_sweep(app, registry, execution);
  rlrun::cli::Action report = rlrun::cli::add_report(app);
  rlrun::cli::Action plot = rlrun::cli::add_plot(app);
  rlrun::cli::Action zoo = rlrun::cli::add_zoo(app, registry);
  rlrun::cli::Action export_policy = rlrun::cli::add_export(app, registry);
  rlrun::cli::Action tune = rlrun::cli::add_tune(app, registry, execution);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    if (const auto message = rlrun::cli::describe_parse_error(app, e, argc, argv)) {
      print_error(*message);
      return rlrun::kExitUsage;
    }
    const int code = app.exit(e);
    return code == 0 ? rlrun::kExitOk : rlrun::kExitUsage;
  }
  try {
    // Checked for every command; the threads themselves only for those that train.
    const int thread_count = rlrun::cli::threads_for_run(threads);
    if (app.got_subcommand("train") || app.got_subcommand("sweep") || app.got_subcommand("tune")) {
      pool.emplace(thread_count);
      execution.pool = &*pool;
    }
    try {
      rlrun::apply_process_environment();  // the RLRUN_* variables, once, before any work
    } catch (const std::runtime_error& e) {
      throw rlrun::UsageError(std::string("RLRUN_KERNELS=") + e.what());
    }
    if (app.got_subcommand("train")) return train();
    if (app.got_subcommand("eval")) return eval();
    if (app.got_subcommand("list")) return list();
    if (app.got_subcommand("check-env")) return check_env();
    if (app.got_subcommand("record")) return record();
    if (app.got_subcommand("sweep")) return sweep();
    if (app.got_subcommand("report")) return report();
    if (app.got_subcommand("plot")) return plot();
    if (app.got_subcommand("zoo")) return zoo();
    if (app.got_subcommand("export")) return export_policy();
    if (app.got_subcommand("tune")) return tune();
  } catch (const rlrun::Interrupted& e) {
    print_error(e.what());
    return 128 + e.signal();
  } catch (const rlrun::ConfigError& e) {
    print_error(e.what());
    return rlrun::kExitUsage;
  } catch (const rlrun::UsageError& e) {
    print_error(e.what());
    return rlrun::kExitUsage;
  } catch (const rlrun::RuntimeFailure& e) {
    print_error(e.what());
    return rlrun::kExitRuntime;
  } catch (const std::bad_alloc&) {
    // Config values are bounded when parsed (core/resource_limits.hpp); this is the machine
    // running out while training, e.g. other processes took the memory.
    print_error(
        "out of memory (std::bad_alloc); free memory, or reduce buffer_size, n_envs or "
        "net_arch");
    return rlrun::kExitRuntime;
  } catch (const std::exception& e) {
    print_error(e.what());
    return rlrun::kExitRuntime;
  }
  return rlrun::kExitUsage;
}
