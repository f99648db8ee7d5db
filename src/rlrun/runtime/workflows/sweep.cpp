#include "rlrun/runtime/workflows/sweep.hpp"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <map>

#include "rlrun/core/config_fields.hpp"
#include "rlrun/core/errors.hpp"
#include "rlrun/runtime/experiment/experiment.hpp"
#include "rlrun/runtime/io/run_directory.hpp"
#include "rlrun/runtime/run/trainer.hpp"

namespace rlrun {

namespace fs = std::filesystem;

namespace {

struct SweepFile {
  std::string name;
  std::string base;
  std::string out_dir;
  std::vector<int64_t> seeds{1};
  ConfigNode grid, list, set;
  SlurmOptions slurm;

  template <class V>
  void visit(V& v) {
    v("name", name, "the sweep's name (default: the file's stem)");
    v("base", base, "the experiment file every run starts from (relative to this file)");
    v("out_dir", out_dir,
      "where manifest.yaml, configs/ and runs/ go (default runs/sweeps/<name>)");
    v("seeds", seeds, "run.seed values; every configuration runs once per seed");
    v("grid", grid, "key: [values...] per overridden key; runs the cartesian product");
    v("list", list, "a list of {key: value} maps, one configuration each (instead of grid)");
    v("set", set, "key: value overrides for every run");
    v("slurm", slurm, "sbatch options for `rlrun sweep slurm`");
  }
};

struct Override {
  std::string key, value;  // value as YAML text
  ConfigNode node;         // the value, where it was written
  ConfigNode map;          // the map holding the key (errors point at the key)
};

// File-name-safe: letters, digits and . _ + - stay, anything else becomes '-'.
std::string safe(const std::string& text) {
  std::string out;
  for (char c : text)
    out += (std::isalnum(static_cast<unsigned char>(c)) || c == '.' || c == '_' || c == '+' ||
            c == '-')
               ? c
               : '-';
  return out;
}

std::string last_component(const std::string& key) {
  const size_t dot = key.rfind('.');
  return dot == std::string::npos ? key : key.substr(dot + 1);
}

std::vector<Override> map_overrides(const ConfigNode& map) {
  if (!map.is_map()) map.fail("expected a map of key: value");
  std::vector<Override> out;
  for (const std::string& key : map.keys()) {
    const ConfigNode value = map.child(key);
    out.push_back({key, yaml_override_text(value.yaml()), value, map});
  }
  return out;
}

// The sweep file's own checks: a base, seeds in run.seed's range, a grid or a list.
void check_sweep_file(const ConfigNode& root, const SweepFile& file) {
  check_slurm_options(root.child("slurm"), file.slurm);
  if (file.base.empty()) root.fail("base: missing (the experiment file every run starts from)");
  if (file.seeds.empty()) root.child("seeds").fail("needs at least one seed");
  for (size_t i = 0; i < file.seeds.size(); ++i)  // run.seed's range (a uint64 read as int64)
    if (file.seeds[i] < 0)
      root.child("seeds").at(i).fail("seeds are integers from 0 to 2^63 - 1, got " +
                                     std::to_string(file.seeds[i]));
  if (file.grid.defined() && file.list.defined())
    root.child("list").fail("a sweep has a grid or a list of configurations, not both");
}

using Combination = std::vector<Override>;

// The grid's cartesian product (keys in file order). The number of runs is known before
// anything is expanded: 8 axes of 10 values are 10^8 runs, which no sweep means; it is refused
// instead of built.
std::vector<Combination> grid_combinations(const SweepFile& file) {
  double runs = static_cast<double>(file.seeds.size());
  for (const Override& axis : map_overrides(file.grid))
    runs *= static_cast<double>(std::max<std::size_t>(axis.node.size(), 1));
  if (runs > kMaxSweepRuns)
    file.grid.fail("the grid gives " + std::to_string(static_cast<long long>(runs)) +
                   " runs (values per key multiplied, times the seeds); a sweep has at most " +
                   std::to_string(kMaxSweepRuns));
  std::vector<Combination> combos{{}};
  for (const Override& axis : map_overrides(file.grid)) {
    if (!axis.node.is_sequence() || axis.node.size() == 0)
      axis.node.fail("expected a non-empty list of values, e.g. [3.0e-4, 1.0e-3]");
    std::vector<Combination> next;
    for (const auto& combo : combos)
      for (size_t i = 0; i < axis.node.size(); ++i) {
        auto extended = combo;
        extended.push_back(
            {axis.key, yaml_override_text(axis.node.at(i).yaml()), axis.node.at(i), axis.map});
        next.push_back(extended);
      }
    combos = next;
  }
  return combos;
}

// The configurations: the grid's product, the list's entries, or the base alone.
std::vector<Combination> combinations(const SweepFile& file) {
  if (file.grid.defined()) return grid_combinations(file);
  if (!file.list.defined()) return {{}};
  if (!file.list.is_sequence() || file.list.size() == 0)
    file.list.fail("expected a non-empty list of {key: value} maps");
  if (static_cast<double>(file.list.size()) * static_cast<double>(file.seeds.size()) >
      kMaxSweepRuns)
    file.list.fail("the list times the seeds gives more than " + std::to_string(kMaxSweepRuns) +
                   " runs");
  std::vector<Combination> combos;
  for (size_t i = 0; i < file.list.size(); ++i) combos.push_back(map_overrides(file.list.at(i)));
  return combos;
}

// Every key must exist in the base experiment: checked one by one, so the error points at the
// sweep file's line rather than at a generated `--set`.
void check_overrides(const std::string& base, const Combination& common,
                     const std::vector<Combination>& combos, Registry& registry) {
  const auto check = [&](const Override& o) {
    try {
      load_experiment(base, {o.key + "=" + o.value}, registry);
    } catch (const ConfigError& e) {
      o.map.fail_at_key(o.key, o.key + " = " + o.value + " does not fit " + base + ": " + e.what());
    }
  };
  for (const Override& o : common) check(o);
  for (const auto& combo : combos)
    for (const Override& o : combo) check(o);
}

// A label names each overridden key by its last component unless another key shares it
// ("learning_rate=0.001"; "base" without overrides); a repeated list entry gets _2, _3, ...
std::vector<std::string> labels(const std::vector<Combination>& combos) {
  std::vector<std::string> short_names;
  for (const auto& combo : combos)
    for (const Override& o : combo) short_names.push_back(last_component(o.key));
  std::vector<std::string> out;
  std::map<std::string, int> uses;
  for (const auto& combo : combos) {
    std::string label;
    for (const Override& o : combo) {
      const std::string short_name = last_component(o.key);
      const bool unique = std::count(short_names.begin(), short_names.end(), short_name) <=
                          static_cast<long>(combos.size());
      // Appended piece by piece: `("" or "_") + ...` trips GCC 12's -Wrestrict false positive.
      if (!label.empty()) label += '_';
      label += safe(unique ? short_name : o.key);
      label += '=';
      label += safe(o.value);
    }
    if (label.empty()) label = "base";
    if (uses[label]++ > 0) label += "_" + std::to_string(uses[label]);
    out.push_back(label);
  }
  return out;
}

// True when the base experiment or the sweep's overrides name run.tensorboard_log.
bool sets_tensorboard_log(const std::string& base, const std::vector<std::string>& overrides) {
  for (const std::string& o : overrides)
    if (o.rfind("run.tensorboard_log=", 0) == 0) return true;
  return ConfigNode::load_file(base).child("run").child("tensorboard_log").defined();
}

// One run: its resolved config written to <out_dir>/configs/, its directory under runs/.
SweepRun expand_run(const Sweep& sweep, const fs::path& out_dir, const std::string& base,
                    const std::string& label, const std::vector<std::string>& overrides,
                    int64_t seed, Registry& registry) {
  SweepRun run;
  run.index = static_cast<int>(sweep.runs.size());
  run.label = label;
  run.seed = static_cast<uint64_t>(seed);
  run.id = label + "/seed" + std::to_string(seed);
  std::vector<std::string> all = overrides;
  all.push_back("run.seed=" + std::to_string(seed));
  // Quoted: a path may hold text YAML would read otherwise (" #" starts a comment).
  all.push_back("run.out_dir=" + yaml_double_quoted((out_dir / "runs").string()));
  all.push_back("run.name=" + yaml_double_quoted(label));
  // TensorBoard: every run of the sweep under one log directory (the sweep's own unless the
  // experiment names one), each run named by its id, so TensorBoard compares them side by side.
  if (!sets_tensorboard_log(base, overrides))
    all.push_back("run.tensorboard_log=" +
                  yaml_double_quoted(sweep_tensorboard_dir(out_dir.string())));
  all.push_back("run.tb_log_name=" + yaml_double_quoted(label + "_seed" + std::to_string(seed)));
  const Experiment experiment = load_experiment(base, all, registry);
  run.config = (out_dir / "configs" / (label + "_seed" + std::to_string(seed) + ".yaml")).string();
  write_text_atomic(run.config, "# run " + run.id + " of sweep " + sweep.source +
                                    " (written by rlrun sweep)\n" + dump_yaml(experiment.resolved));
  run.run_dir = (out_dir / "runs" / label / ("seed" + std::to_string(seed))).string();
  return run;
}

void write_manifest(const Sweep& sweep, const fs::path& out_dir) {
  YAML::Emitter out;
  out << YAML::BeginMap << YAML::Key << "sweep" << YAML::Value << sweep.source << YAML::Key
      << "name" << YAML::Value << sweep.name << YAML::Key << "slurm" << YAML::Value
      << encode(sweep.slurm) << YAML::Key << "runs" << YAML::Value << YAML::BeginSeq;
  for (const SweepRun& run : sweep.runs) {
    out << YAML::Flow << YAML::BeginMap << YAML::Key << "index" << YAML::Value << run.index
        << YAML::Key << "id" << YAML::Value << run.id << YAML::Key << "seed" << YAML::Value
        << run.seed << YAML::Key << "config" << YAML::Value
        << fs::relative(run.config, out_dir).string() << YAML::Key << "run_dir" << YAML::Value
        << fs::relative(run.run_dir, out_dir).string() << YAML::EndMap;
  }
  out << YAML::EndSeq << YAML::EndMap;
  write_text_atomic(sweep.manifest, "# rlrun sweep manifest: `rlrun sweep run " + sweep.manifest +
                                        "` trains the runs (paths relative to this file)\n" +
                                        out.c_str() + "\n");
}

// The command line's --set values, each checked against the base experiment (the command
// line is trusted, like the sweep file) and refused when the grid or list varies its key: one
// value for every run would silently undo the sweep.
Combination command_line_overrides(const std::string& base, const std::vector<std::string>& set,
                                   const std::vector<Combination>& combos, Registry& registry) {
  Combination out;
  for (const std::string& assignment : set) {
    const size_t eq = assignment.find('=');
    if (eq == std::string::npos || eq == 0)
      throw UsageError("--set " + assignment +
                       ": expected key=value, e.g. --set run.total_timesteps=20000");
    const std::string key = assignment.substr(0, eq);
    for (const auto& combo : combos)
      for (const Override& o : combo)
        if (o.key == key)
          throw UsageError("--set " + assignment + ": the sweep varies " + key +
                           " (grid or list); --set gives every run the same value");
    try {
      load_experiment(base, {assignment}, registry);
    } catch (const ConfigError& e) {
      throw ConfigError("--set " + assignment + " does not fit " + base + ": " + e.what());
    }
    out.push_back({key, assignment.substr(eq + 1), ConfigNode(), ConfigNode()});
  }
  return out;
}

}  // namespace

Sweep expand_sweep(const std::string& sweep_file, Registry& registry, const SweepOptions& options) {
  const ConfigNode root = ConfigNode::load_file(sweep_file);
  SweepFile file;
  decode(root, file);
  check_sweep_file(root, file);
  const fs::path here = fs::path(sweep_file).parent_path();
  const std::string base =
      fs::path(file.base).is_absolute() ? file.base : (here / file.base).string();
  if (!fs::exists(base)) root.child("base").fail(base + " does not exist");
  const std::vector<Combination> combos = combinations(file);
  Combination common = file.set.defined() ? map_overrides(file.set) : Combination{};
  check_overrides(base, common, combos, registry);
  for (Override& o : command_line_overrides(base, options.set, combos, registry))
    common.push_back(std::move(o));  // after the file's set: the command line wins

  Sweep sweep;
  sweep.name = file.name.empty() ? fs::path(sweep_file).stem().string() : file.name;
  const std::string chosen_out = !options.out_dir.empty() ? options.out_dir : file.out_dir;
  const fs::path out_dir =
      fs::absolute(chosen_out.empty() ? fs::path("runs/sweeps") / sweep.name : fs::path(chosen_out))
          .lexically_normal();
  sweep.source = fs::absolute(sweep_file).lexically_normal().string();
  sweep.manifest = (out_dir / "manifest.yaml").string();
  sweep.slurm = file.slurm;
  fs::create_directories(out_dir / "configs");
  const std::vector<std::string> run_labels = labels(combos);
  for (size_t c = 0; c < combos.size(); ++c) {
    std::vector<std::string> overrides;
    for (const Override& o : common) overrides.push_back(o.key + "=" + o.value);
    for (const Override& o : combos[c]) overrides.push_back(o.key + "=" + o.value);
    for (int64_t seed : file.seeds)
      sweep.runs.push_back(
          expand_run(sweep, out_dir, base, run_labels[c], overrides, seed, registry));
  }
  write_manifest(sweep, out_dir);
  return sweep;
}

namespace {

// `dir / relative` when `relative` names a path strictly inside `dir` (no absolute path, no
// '..' part, no control characters); else a ConfigError at the value.
std::string inside(const fs::path& dir, const ConfigNode& value) {
  const std::string text = value.as_string();
  const std::string problem = RelativeName{}.problem(text);
  if (!problem.empty()) value.fail(problem + " (manifest paths stay inside its directory)");
  return (dir / text).lexically_normal().string();
}

}  // namespace

Sweep read_manifest(const std::string& manifest) {
  if (!fs::exists(manifest))
    throw UsageError(manifest + " does not exist (write it with `rlrun sweep SWEEP.yaml`)");
  const ConfigNode root = ConfigNode::load_file(manifest, ConfigTrust::kUntrusted);
  const fs::path dir = fs::absolute(manifest).parent_path();
  Sweep sweep;
  sweep.manifest = fs::absolute(manifest).lexically_normal().string();
  sweep.source = root.child("sweep").as_string();
  sweep.name = root.child("name").as_string();
  decode(root.child("slurm"), sweep.slurm);
  // A manifest is not trusted (docs/security.md): its slurm options become #SBATCH lines.
  check_slurm_options(root.child("slurm"), sweep.slurm);
  const ConfigNode runs = root.child("runs");
  if (!runs.is_sequence()) root.fail("runs: expected the list of runs");
  for (size_t i = 0; i < runs.size(); ++i) {
    const ConfigNode r = runs.at(i);
    SweepRun run;
    run.index = static_cast<int>(r.child("index").as_int());
    run.id = r.child("id").as_string();
    const int64_t seed = r.child("seed").as_int();
    if (seed < 0) r.child("seed").fail("seeds are integers from 0 to 2^63 - 1");
    run.seed = static_cast<uint64_t>(seed);
    run.label = run.id.substr(0, run.id.rfind('/'));
    // A manifest may come from anyone: its paths must stay inside its own directory, since
    // `sweep run` writes (and for a run restarted from scratch, deletes) the run directory.
    run.config = inside(dir, r.child("config"));
    run.run_dir = inside(dir, r.child("run_dir"));
    if (run.index != static_cast<int>(i))
      r.child("index").fail("expected index " + std::to_string(i));
    sweep.runs.push_back(run);
  }
  return sweep;
}

RunState run_state(const SweepRun& run) {
  if (!fs::exists(run.run_dir)) return RunState::kNew;
  if (fs::exists(fs::path(run.run_dir) / kFinishedMarker)) return RunState::kFinished;
  const fs::path checkpoints = fs::path(run.run_dir) / "checkpoints";
  if (fs::exists(checkpoints))
    for (const auto& entry : fs::directory_iterator(checkpoints))
      if (entry.path().extension() == ".zip") return RunState::kResumable;
  return RunState::kPartial;
}

std::string sweep_tensorboard_dir(const std::string& sweep_out_dir) {
  return (fs::path(sweep_out_dir) / "tensorboard").string();
}

std::vector<std::string> sweep_vouched_overrides(const Sweep& sweep, const SweepRun& run) {
  // The manifest's directory is the sweep's out_dir; a run's config naming the sweep's own
  // TensorBoard directory writes inside the sweep, as its run directories do.
  const std::string own = sweep_tensorboard_dir(fs::path(sweep.manifest).parent_path().string());
  try {
    const ConfigNode config = ConfigNode::load_file(run.config, ConfigTrust::kUntrusted);
    const ConfigNode named = config.child("run").child("tensorboard_log");
    if (named.defined() && named.as_string() == own)
      return {"run.tensorboard_log=" + yaml_double_quoted(own)};
  } catch (const ConfigError&) {
    // An unreadable config is reported when the run loads it.
  }
  return {};
}

bool run_config_matches(const SweepRun& run) {
  const fs::path trained = fs::path(run.run_dir) / "config.yaml";
  if (!fs::exists(trained)) return true;
  // Both are dump_yaml() of a resolved experiment; compare them parsed (comments aside). Both
  // are untrusted (a run directory, a manifest's config): read within the config bounds, and a
  // file that cannot be read does not match.
  try {
    const ConfigNode a = ConfigNode::load_file(trained.string(), ConfigTrust::kUntrusted);
    const ConfigNode b = ConfigNode::load_file(run.config, ConfigTrust::kUntrusted);
    return dump_yaml(a.yaml()) == dump_yaml(b.yaml());
  } catch (const ConfigError&) {
    return false;
  }
}

std::string run_console_log(const Sweep& sweep, const SweepRun& run) {
  const fs::path out_dir = fs::path(sweep.manifest).parent_path();
  const fs::path below = fs::path(run.run_dir).lexically_relative(out_dir / "runs");
  const bool inside = !below.empty() && *below.begin() != ".." && below != ".";
  return (out_dir / "logs" / (inside ? below : fs::path("run" + std::to_string(run.index))))
             .string() +
         ".txt";
}

const char* to_string(RunState state) {
  switch (state) {
    case RunState::kNew: return "new";
    case RunState::kFinished: return "finished";
    case RunState::kResumable: return "resumable";
    case RunState::kPartial: return "partial";
  }
  return "?";
}

}  // namespace rlrun
