#include "rlrun/runtime/io/run_results.hpp"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <numeric>
#include <sstream>

#include "rlrun/core/config_node.hpp"
#include "rlrun/core/dir_handle.hpp"
#include "rlrun/core/errors.hpp"
#include "rlrun/rng.hpp"
#include "rlrun/runtime/experiment/experiment.hpp"
#include "rlrun/runtime/io/agent_team_file.hpp"
#include "rlrun/runtime/io/log_sinks.hpp"
#include "rlrun/runtime/io/model_file.hpp"
#include "rlrun/runtime/io/run_directory.hpp"
#include "rlrun/runtime/io/run_file_bounds.hpp"
#include "rlrun/runtime/io/session_summary.hpp"

namespace rlrun {

namespace fs = std::filesystem;

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr int kLastEpisodes = 100;  // SB3's ep_info_buffer: rollout/ep_rew_mean's window
constexpr int kBootstrapSamples = 2000;
constexpr uint64_t kBootstrapSeed = 0;

double number(const std::string& cell) {
  if (cell.empty()) return kNaN;
  try {
    return std::stod(cell);
  } catch (const std::exception&) {
    return kNaN;
  }
}

// A CSV file of the run as columns (empty when it does not exist); a first line starting with
// '#' is skipped (Monitor files). Read within the bounds of runtime/io/run_file_bounds.hpp.
std::map<std::string, std::vector<double>> read_columns(const DirHandle& run,
                                                        const std::string& name) {
  std::map<std::string, std::vector<double>> columns;
  std::optional<LineReader> in = run.read_lines(name, kMaxRunCsvBytes, kMaxRunCsvLineBytes);
  if (!in) return columns;
  std::string line;
  while (in->next(line) && !line.empty() && line[0] == '#') {
  }
  if (line.empty()) return columns;
  const std::vector<std::string> header = split_csv_line(line);
  std::vector<std::vector<double>*> column_of;
  for (const auto& key : header) column_of.push_back(&columns[key]);
  uint64_t values = 0;
  while (in->next(line)) {
    if (line.empty()) continue;
    values += header.size();
    if (values > kMaxRunCsvValues)
      throw RuntimeFailure(in->shown() + " holds more than " + std::to_string(kMaxRunCsvValues) +
                           " values, the most rlrun reads of a CSV file (docs/security.md)");
    const std::vector<std::string> cells = split_csv_line(line);
    for (size_t i = 0; i < header.size(); ++i)
      column_of[i]->push_back(i < cells.size() ? number(cells[i]) : kNaN);
  }
  return columns;
}

double last_finite(const std::vector<double>& v) {
  for (auto it = v.rbegin(); it != v.rend(); ++it)
    if (std::isfinite(*it)) return *it;
  return kNaN;
}

double percentile(std::vector<double> v, double p) {  // numpy's default, linear
  std::sort(v.begin(), v.end());
  const double pos = p / 100.0 * (v.size() - 1);
  const size_t lo = static_cast<size_t>(std::floor(pos)), hi = std::min(lo + 1, v.size() - 1);
  return v[lo] + (pos - lo) * (v[hi] - v[lo]);
}

}  // namespace

std::vector<std::string> find_run_dirs(const std::vector<std::string>& paths) {
  // The paths named are the user's (followed); below them, links are not: a run directory
  // must be a directory itself (core/dir_handle.hpp), and the search does not enter links.
  const auto is_real_directory = [](const fs::path& p) {
    std::error_code ec;
    return fs::is_directory(fs::symlink_status(p, ec));
  };
  const auto exists_here = [](const fs::path& p) {
    std::error_code ec;
    return fs::exists(fs::symlink_status(p, ec));
  };
  std::vector<std::string> dirs;
  for (const std::string& path : paths) {
    if (!fs::is_directory(path)) throw UsageError(path + " is not a directory");
    const size_t before = dirs.size();
    // A per-agent run's team directory (runtime/io/agent_team_file.hpp) holds no training data
    // of its own: its agents' run directories below it are the runs.
    if (exists_here(fs::path(path) / "config.yaml") &&
        !exists_here(fs::path(path) / kAgentTeamFile)) {
      dirs.push_back(path);
    } else {
      for (const auto& entry : fs::recursive_directory_iterator(path))
        if (is_real_directory(entry.path()) && exists_here(entry.path() / "config.yaml") &&
            exists_here(entry.path() / "progress.csv"))
          dirs.push_back(entry.path().string());
    }
    if (dirs.size() == before)
      throw UsageError(path + " holds no run directory (config.yaml + progress.csv)");
  }
  std::sort(dirs.begin(), dirs.end());
  dirs.erase(std::unique(dirs.begin(), dirs.end()), dirs.end());
  return dirs;
}

namespace {

// The run.* keys that are not part of a configuration: what differs between the seeds of one
// (the seed, and the TensorBoard run name `rlrun sweep` derives from it: <label>_seed<N>) and
// where its outputs go. Two runs whose configs differ only there are seeds of one group.
constexpr const char* kNotConfiguration[] = {"seed", "out_dir", "tb_log_name", "tensorboard_log"};

// The run's config.yaml: a run directory may come from anyone (docs/security.md), so it is read
// with the same bounds as any untrusted config text (size, alias expansion, one document).
// Fills seed and name; returns the resolved config without kNotConfiguration (the group key).
std::string read_run_config(const DirHandle& run_dir, RunResult& r) {
  const std::optional<std::string> text = run_dir.read("config.yaml", kMaxConfigBytes + 1);
  if (!text) throw RuntimeFailure(run_dir.path() + " has no config.yaml: not a run directory");
  try {
    const ConfigNode root =
        ConfigNode::load_string(*text, run_dir.child("config.yaml"), ConfigTrust::kUntrusted);
    const ConfigNode run = root.child("run");
    if (run.child("seed").defined()) r.seed = static_cast<uint64_t>(run.child("seed").as_int());
    if (run.child("name").defined()) r.name = run.child("name").as_string();
    YAML::Node node = YAML::Clone(root.yaml());
    // A config.yaml that is a scalar or a list (not rlrun's) has no run section to drop; a
    // non-const operator[] on it would throw yaml-cpp's BadSubscript (found by fuzz_run_dir).
    if (node.IsMap() && node["run"].IsMap())
      for (const char* key : kNotConfiguration) node["run"].remove(key);
    return dump_yaml(node);
  } catch (const ConfigError& e) {
    throw RuntimeFailure(std::string(e.what()) + " (not a run directory written by rlrun?)");
  }
}

// The sessions' summary lines of log.txt added up (a resumed run has several; one per
// `train` or `train --resume`, runtime/io/session_summary.hpp); NaN when there is none.
double logged_wall_seconds(const DirHandle& run) {
  std::optional<LineReader> log =
      run.read_lines("log.txt", kMaxRunLogBytes, kMaxRunLogLineBytes, LineReader::LongLines::kCut);
  bool logged = false;
  double seconds = 0;
  for (std::string line; log && log->next(line);) {
    const std::optional<SessionSummary> session = parse_session_summary(line);
    if (!session) continue;
    seconds += session->wall_seconds;
    logged = true;
  }
  return logged ? seconds : kNaN;
}

// The run's step count. progress.csv's last row is not it: DQN/SAC/TD3/DDPG log a row every
// log_interval episodes, so a 5000-step run may have logged last at step 2880. The `finished`
// marker (written last, "timesteps N") is the count of a finished run; otherwise model.zip's
// meta.json (written at the end of every session, also an interrupted one), unless progress.csv
// got further (a run training now, after a resume).
double true_timesteps(const DirHandle& run, double progress_timesteps) {
  std::istringstream marker(run.read(kFinishedMarker, kMaxRunMarkerBytes).value_or(""));
  std::string word;
  long long steps = 0;
  if (marker >> word >> steps && word == "timesteps" && steps >= 0)
    return static_cast<double>(steps);
  double best = std::isfinite(progress_timesteps) ? progress_timesteps : 0.0;
  if (run.kind("model.zip") == EntryKind::kRegular) {  // a link is not followed
    try {  // meta.json only, within its bound (model files are untrusted: model_file.hpp)
      const ModelFile header = read_model_header(run.child("model.zip"));
      best = std::max(best, static_cast<double>(header.meta.num_timesteps));
    } catch (const std::exception&) {
      // A damaged model.zip: progress.csv's count stands.
    }
  }
  return best;
}

// The mean of the last 100 training episodes over all monitor files, in the order they ended
// (and their success rate when the monitor has is_success); source "none" without episodes.
void monitor_return(const DirHandle& run, RunResult& r) {
  std::vector<std::pair<double, double>> episodes;  // (t, r)
  std::vector<std::pair<double, double>> successes;
  for (const DirHandle::Entry& entry : run.list()) {
    const std::string& file = entry.name;
    if (file.size() < 12 || file.substr(file.size() - 12) != ".monitor.csv") continue;
    const auto m = read_columns(run, file);
    if (!m.count("r") || !m.count("t")) continue;
    for (size_t i = 0; i < m.at("r").size(); ++i) {
      episodes.emplace_back(m.at("t")[i], m.at("r")[i]);
      if (m.count("is_success")) successes.emplace_back(m.at("t")[i], m.at("is_success")[i]);
    }
  }
  if (episodes.empty()) {  // e.g. stopped before its first episode ended: curves only
    r.final_return = kNaN;
    r.return_source = "none";
    return;
  }
  const auto mean_of_last = [](std::vector<std::pair<double, double>> v) {
    std::stable_sort(v.begin(), v.end(),
                     [](const auto& a, const auto& b) { return a.first < b.first; });
    const size_t from = v.size() > kLastEpisodes ? v.size() - kLastEpisodes : 0;
    double sum = 0;
    for (size_t i = from; i < v.size(); ++i) sum += v[i].second;
    return sum / static_cast<double>(v.size() - from);
  };
  r.final_return = mean_of_last(episodes);
  r.return_source = "monitor";
  if (!successes.empty()) r.success_rate = mean_of_last(successes);
}

}  // namespace

RunResult read_run(const std::string& dir) {
  RunResult r;
  r.dir = dir;
  const DirHandle run = DirHandle::open(dir);  // a run directory: not a link (dir_handle.hpp)
  r.config_key = read_run_config(run, r);
  r.progress = read_columns(run, "progress.csv");
  // Wall time from log.txt, else progress.csv's whole seconds.
  r.wall_seconds = logged_wall_seconds(run);
  if (std::isnan(r.wall_seconds))
    r.wall_seconds =
        r.progress.count("time/time_elapsed") ? last_finite(r.progress["time/time_elapsed"]) : 0.0;
  const auto logged = r.progress.find("time/total_timesteps");
  r.timesteps =
      true_timesteps(run, logged != r.progress.end() ? last_finite(logged->second) : kNaN);
  // The last evaluation when the run evaluated, else the last 100 training episodes.
  const auto evaluations = read_columns(run, "evaluations.csv");
  if (evaluations.count("mean_reward") && !evaluations.at("mean_reward").empty()) {
    r.final_return = evaluations.at("mean_reward").back();
    r.return_source = "eval";
    if (evaluations.count("success_rate") && std::isfinite(evaluations.at("success_rate").back()))
      r.success_rate = evaluations.at("success_rate").back();
    return r;
  }
  monitor_return(run, r);
  return r;
}

std::vector<RunResult> read_runs(const std::vector<std::string>& paths) {
  std::vector<RunResult> runs;
  for (const std::string& dir : find_run_dirs(paths)) runs.push_back(read_run(dir));
  return runs;
}

std::vector<RunGroup> group_runs(const std::vector<RunResult>& runs) {
  std::vector<RunGroup> groups;
  std::vector<std::string> keys;
  for (const RunResult& run : runs) {
    const auto it = std::find(keys.begin(), keys.end(), run.config_key);
    if (it == keys.end()) {
      keys.push_back(run.config_key);
      groups.push_back(
          {run.name.empty() ? fs::path(run.dir).filename().string() : run.name, {run}});
    } else {
      groups[it - keys.begin()].runs.push_back(run);
    }
  }
  std::map<std::string, int> uses;
  for (const RunGroup& g : groups) ++uses[g.label];
  std::map<std::string, int> numbered;
  for (RunGroup& g : groups) {
    if (uses[g.label] > 1) g.label += " #" + std::to_string(++numbered[g.label]);
    std::sort(g.runs.begin(), g.runs.end(),
              [](const auto& a, const auto& b) { return a.seed < b.seed; });
  }
  return groups;
}

double interquartile_mean(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const size_t cut = static_cast<size_t>(0.25 * static_cast<double>(v.size()));  // scipy trim_mean
  const size_t end = v.size() - cut;
  if (end <= cut) return kNaN;
  return std::accumulate(v.begin() + cut, v.begin() + end, 0.0) / static_cast<double>(end - cut);
}

SeedStatistics seed_statistics(const std::vector<double>& all) {
  std::vector<double> values;
  for (double v : all)
    if (std::isfinite(v)) values.push_back(v);
  SeedStatistics s;
  s.n = static_cast<int>(values.size());
  if (values.empty()) return s;
  s.mean = std::accumulate(values.begin(), values.end(), 0.0) / s.n;
  double sq = 0;
  for (double v : values) sq += (v - s.mean) * (v - s.mean);
  s.std = std::sqrt(sq / s.n);
  s.median = percentile(values, 50);
  s.iqm = interquartile_mean(values);
  Rng rng(kBootstrapSeed);
  std::vector<double> estimates, sample(values.size());
  estimates.reserve(kBootstrapSamples);
  for (int b = 0; b < kBootstrapSamples; ++b) {
    for (double& x : sample) x = values[rng.below(values.size())];
    estimates.push_back(interquartile_mean(sample));
  }
  s.iqm_low = percentile(estimates, 2.5);
  s.iqm_high = percentile(estimates, 97.5);
  return s;
}

}  // namespace rlrun
