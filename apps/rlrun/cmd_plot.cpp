// rlrun plot RUN_DIRS... --output curves.png|svg [--metric rollout/ep_rew_mean] [--title T]:
// learning curves from progress.csv, one line per configuration (mean over seeds) with a band
// over seeds (render/learning_curves.hpp).
#include <algorithm>
#include <cstdio>

#include "commands.hpp"
#include "rlrun/core/config_node.hpp"
#include "rlrun/core/errors.hpp"
#include "rlrun/core/plural.hpp"
#include "rlrun/render/learning_curves.hpp"
#include "rlrun/runtime/io/run_results.hpp"

namespace rlrun::cli {

namespace {

// progress.csv's data rows (0 for an empty file or a header alone).
size_t progress_rows(const RunResult& r) {
  size_t rows = 0;
  for (const auto& [name, values] : r.progress) rows = std::max(rows, values.size());
  return rows;
}

}  // namespace

Action add_plot(CLI::App& app) {
  struct Options {
    std::vector<std::string> paths;
    std::string output, metric = "rollout/ep_rew_mean", title;
  };
  auto options = std::make_shared<Options>();
  CLI::App* sub = app.add_subcommand("plot", "learning curves of runs (PNG or SVG)");
  sub->add_option("run_dirs", options->paths, "run directories, or directories holding them")
      ->required();
  sub->add_option("-o,--output", options->output, "curves.png or curves.svg")->required();
  sub->add_option("--metric", options->metric,
                  "a progress.csv column (default rollout/ep_rew_mean)");
  sub->add_option("--title", options->title, "the plot's title (default: the metric)");
  return [options]() {
    std::vector<RunResult> runs;
    std::vector<std::string> empty;  // runs that have logged no row yet: nothing to draw
    for (RunResult& r : read_runs(options->paths)) {
      if (progress_rows(r) == 0)
        empty.push_back(r.dir);
      else
        runs.push_back(std::move(r));
    }
    if (runs.empty())
      throw RuntimeFailure(
          (empty.size() == 1 ? empty.front() + "/progress.csv has"
                             : "the progress.csv of each of the " +
                                   count_of(static_cast<int64_t>(empty.size()), "run") + " has") +
          " no rows yet (nothing logged so far: a row comes every run.log_interval iterations, "
          "or episodes for DQN/SAC/TD3/DDPG); plot again once training has logged");
    for (const std::string& dir : empty)
      std::printf("note: left out %s: its progress.csv has no rows yet\n", dir.c_str());
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
                           "/progress.csv has no such column" +
                           did_you_mean(options->metric, names) + "; it has " + columns);
        }
        if (x == r.progress.end())
          throw RuntimeFailure(r.dir + "/progress.csv has no time/total_timesteps");
        std::vector<std::pair<double, double>> points;
        for (size_t i = 0; i < x->second.size() && i < y->second.size(); ++i)
          points.emplace_back(x->second[i], y->second[i]);
        curves.seeds.push_back(points);
      }
      groups.push_back(curves);
    }
    const std::string title =
        options->title.empty() ? options->metric + " over training" : options->title;
    plot_learning_curves(groups, options->metric, title, options->output);
    std::printf("plotted %s (%s) -> %s\n",
                count_of(static_cast<int64_t>(groups.size()), "configuration").c_str(),
                count_of(static_cast<int64_t>(runs.size()), "run").c_str(),
                options->output.c_str());
    return 0;
  };
}

}  // namespace rlrun::cli
