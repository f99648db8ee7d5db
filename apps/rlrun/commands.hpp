#pragma once
// One function per subcommand (ninja's subcommand-table style): each registers its options on
// the CLI11 app and returns the action to run after parsing.
#include <CLI/CLI.hpp>
#include <functional>

namespace rlrun::cli {

using Action = std::function<int()>;

Action add_train(CLI::App& app);
Action add_eval(CLI::App& app);
Action add_list(CLI::App& app);
Action add_check_env(CLI::App& app);
Action add_record(CLI::App& app);
Action add_sweep(CLI::App& app);
Action add_report(CLI::App& app);
Action add_plot(CLI::App& app);

}  // namespace rlrun::cli
