#pragma once
// One function per subcommand (ninja's subcommand-table style): each registers its options on
// the CLI11 app and returns the action to run after parsing.
#include <CLI/CLI.hpp>
#include <functional>

#include "rlrun/core/execution_context.hpp"
#include "rlrun/runtime/components/registry.hpp"

namespace rlrun::cli {

using Action = std::function<int()>;

// `registry` is main()'s: the built-in components, to which `--plugin` adds libraries. It
// outlives the actions. So does `execution` (the run's threads), filled in once the options
// are read.
Action add_train(CLI::App& app, Registry& registry, const ExecutionContext& execution);
Action add_eval(CLI::App& app, Registry& registry);
Action add_list(CLI::App& app, Registry& registry);
Action add_check_env(CLI::App& app, Registry& registry);
Action add_record(CLI::App& app, Registry& registry);
Action add_sweep(CLI::App& app, Registry& registry, const ExecutionContext& execution);
Action add_report(CLI::App& app);
Action add_plot(CLI::App& app);
Action add_zoo(CLI::App& app, Registry& registry);
Action add_export(CLI::App& app, Registry& registry);
Action add_tune(CLI::App& app, Registry& registry, const ExecutionContext& execution);

}  // namespace rlrun::cli
