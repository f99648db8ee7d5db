// rlrun plot RUN_DIRS... --output curves.png|svg [--metric rollout/ep_rew_mean] [--title T]:
// learning curves from progress.csv, one line per configuration (mean over seeds) with a band
// over seeds (render/learning_curves.hpp).
#include <cstdio>

#include "commands.hpp"
#include "rlrun/core/config_node.hpp"
#include "rlrun/core/errors.hpp"
#include "rlrun/render/learning_curves.hpp"
#include "rlrun/core/plural.hpp"
#include "rlrun/runtime/run_results.hpp"

namespace rlrun::cli {

Action add_plot(CLI::App& app) {
  struct Options {
    std::vector<std::string> paths;
    std::string output, metric = "rollout/ep_rew_mean", title;
  };
  auto options = std::make_shared<Options>();
  CLI::App* sub = app.add_subcommand("plot", "learning curves of runs (PNG or SVG)");
  sub->add_option("run_dirs", options->paths, "run directories, or directories holding them")->required();
  sub->add_option("-o,--output", options->output, "curves.png or curves.svg")->required();
  sub->add_option("--metric", options->metric, "a progress.csv column (default rollout/ep_rew_mean)");
  sub->add_option("--title", options->title, "the plot's title (default: the metric)");
  return [options]() {
    const std::vector<RunResult> runs = read_runs(options->paths);
    std::vector<CurveGroup> groups;
    for (const RunGroup& group : group_runs(runs)) {
      CurveGroup curves{group.label, {}};
      for (const RunResult& r : group.runs) {
        const auto x = r.progress.find("time/total_timesteps");
        const auto y = r.progress.find(options->metric);
        if (y == r.progress.end()) {
          std::string columns;
          std::vector<std::string> names;
          for (const auto& [name, values] : r.progress) {
            columns += (columns.empty() ? "" : ", ") + name;
            names.push_back(name);
          }
          throw UsageError("--metric " + options->metric + ": " + r.dir +
                           "/progress.csv has no such column" + did_you_mean(options->metric, names) +
                           "; it has " + columns);
        }
        if (x == r.progress.end()) throw RuntimeFailure(r.dir + "/progress.csv has no time/total_timesteps");
        std::vector<std::pair<double, double>> points;
        for (size_t i = 0; i < x->second.size() && i < y->second.size(); ++i)
          points.emplace_back(x->second[i], y->second[i]);
        curves.seeds.push_back(points);
      }
      groups.push_back(curves);
    }
    const std::string title = options->title.empty() ? options->metric + " over training" : options->title;
    plot_learning_curves(groups, options->metric, title, options->output);
    std::printf("plotted %s (%s) -> %s\n",
                count_of(static_cast<int64_t>(groups.size()), "configuration").c_str(),
                count_of(static_cast<int64_t>(runs.size()), "run").c_str(),
                options->output.c_str());
    return 0;
  };
}

}  // namespace rlrun::cli
