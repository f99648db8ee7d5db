// rlrun report RUN_DIRS... [--csv FILE] [--markdown FILE]: per configuration across seeds, the
// final return's mean, std, median and IQM with a bootstrap 95 % CI (runtime/io/run_results.hpp),
// the success rate where the runs record one, wall time and steps/s.
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "commands.hpp"
#include "rlrun/core/errors.hpp"
#include "rlrun/runtime/io/run_results.hpp"

namespace rlrun::cli {

namespace {

std::string fmt(double v, int digits = 2) {
  if (!std::isfinite(v)) return "";
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%.*f", digits, v);
  return buffer;
}

struct Row {
  std::string label, source;
  SeedStatistics stats;
  std::string seeds;
  double success = NAN, wall = 0, steps_per_second = 0, timesteps = 0;
};

void write_file(const std::string& path, const std::string& text) {
  const auto parent = std::filesystem::path(path).parent_path();
  if (!parent.empty()) std::filesystem::create_directories(parent);
  std::ofstream out(path, std::ios::trunc);
  if (!out) throw RuntimeFailure("cannot write " + path);
  out << text;
}

}  // namespace

Action add_report(CLI::App& app) {
  struct Options {
    std::vector<std::string> paths;
    std::string csv, markdown;
  };
  auto options = std::make_shared<Options>();
  CLI::App* sub = app.add_subcommand(
      "report",
      "per configuration across seeds: final return mean, std, median, IQM with a "
      "bootstrap 95 % CI, success rate, wall time, steps/s");
  sub->add_option("run_dirs", options->paths,
                  "run directories, or directories holding them (e.g. a sweep's runs/)")
      ->required();
  sub->add_option("--csv", options->csv, "also write the table as CSV");
  sub->add_option("--markdown", options->markdown, "also write the Markdown table to a file");
  return [options]() {
    const std::vector<RunResult> runs = read_runs(options->paths);
    std::vector<Row> rows;
    for (const RunGroup& group : group_runs(runs)) {
      Row row;
      row.label = group.label;
      std::vector<double> returns;
      double success_sum = 0, wall = 0, steps = 0;
      int with_success = 0;
      for (const RunResult& r : group.runs) {
        returns.push_back(r.final_return);
        row.seeds += (row.seeds.empty() ? "" : " ") + std::to_string(r.seed);
        if (r.success_rate) success_sum += *r.success_rate, ++with_success;
        wall += r.wall_seconds;
        steps += r.timesteps;
        if (row.source.find(r.return_source) == std::string::npos)
          row.source += (row.source.empty() ? "" : "+") + r.return_source;
      }
      const double n = static_cast<double>(group.runs.size());
      row.stats = seed_statistics(returns);
      if (with_success > 0) row.success = success_sum / with_success;
      row.wall = wall / n;
      row.timesteps = steps / n;
      row.steps_per_second = wall > 0 ? steps / wall : 0;
      rows.push_back(row);
    }
    std::ostringstream md, csv;
    md << "| configuration | seeds | final return mean | std | median | IQM [95% CI] | success "
          "rate "
          "| timesteps | wall s | steps/s | return from "
          "|\n|---|---|---|---|---|---|---|---|---|---|---|\n";
    csv << "configuration,n_seeds,seeds,mean,std,median,iqm,iqm_ci_low,iqm_ci_high,success_rate,"
           "timesteps,wall_seconds,steps_per_second,return_source\n";
    for (const Row& r : rows) {
      md << "| " << r.label << " | " << r.stats.n << " (" << r.seeds << ") | " << fmt(r.stats.mean)
         << " | " << fmt(r.stats.std) << " | " << fmt(r.stats.median) << " | " << fmt(r.stats.iqm)
         << " [" << fmt(r.stats.iqm_low) << ", " << fmt(r.stats.iqm_high) << "] | "
         << (std::isfinite(r.success) ? fmt(r.success, 3) : "—") << " | " << fmt(r.timesteps, 0)
         << " | " << fmt(r.wall, 1) << " | " << fmt(r.steps_per_second, 0) << " | " << r.source
         << " |\n";
      csv << r.label << ',' << r.stats.n << ',' << r.seeds << ',' << fmt(r.stats.mean, 6) << ','
          << fmt(r.stats.std, 6) << ',' << fmt(r.stats.median, 6) << ',' << fmt(r.stats.iqm, 6)
          << ',' << fmt(r.stats.iqm_low, 6) << ',' << fmt(r.stats.iqm_high, 6) << ','
          << fmt(r.success, 6) << ',' << fmt(r.timesteps, 0) << ',' << fmt(r.wall, 3) << ','
          << fmt(r.steps_per_second, 1) << ',' << r.source << '\n';
    }
    md << "\nfinal return: the last evaluation's mean (evaluations.csv) where the run evaluated, "
          "else the mean of its last 100 training episodes (monitor files); IQM: mean of the "
          "middle 50 % of seeds, 95 % CI by percentile bootstrap over seeds (2000 resamples).\n";
    std::printf("%s", md.str().c_str());
    if (!options->csv.empty()) write_file(options->csv, csv.str());
    if (!options->markdown.empty()) write_file(options->markdown, md.str());
    return 0;
  };
}

}  // namespace rlrun::cli
