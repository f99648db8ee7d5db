#include "rlrun/runtime/experiment/experiment.hpp"

#include <algorithm>
#include <filesystem>

#include "rlrun/algos/algorithm.hpp"
#include "rlrun/core/config_fields.hpp"
#include "rlrun/core/errors.hpp"
#include "rlrun/core/resource_limits.hpp"
#include "rlrun/runtime/components/plugin_loader.hpp"
#include "rlrun/runtime/experiment/env_factory.hpp"

namespace rlrun {

namespace {

const std::vector<std::string> kSections{"run",     "env",   "algo",      "eval",   "checkpoint",
                                         "obs_log", "video", "self_play", "plugins"};

// Problems found so far, one line each; a step that throws ConfigError adds its lines and
// parsing goes on, so one run of `rlrun train` shows every problem of every file.
class Problems {
 public:
  template <class F>
  bool attempt(F&& step) {
    try {
      step();
      return true;
    } catch (const ConfigError& e) {
      lines_.push_back(e.what());
      return false;
    }
  }
  void add(const std::string& line) { lines_.push_back(line); }
  bool empty() const { return lines_.empty(); }
  void throw_if_any() const {
    if (lines_.empty()) return;
    std::string message;
    for (const auto& line : lines_) message += (message.empty() ? "" : "\n") + line;
    throw ConfigError(message);
  }

 private:
  std::vector<std::string> lines_;
};

std::string required_id(const ConfigNode& section, const char* what) {
  if (!section.defined()) section.fail(std::string("missing section (needs at least `id`)"));
  if (!section.is_map())
    section.fail("expected a map with `id` and " + std::string(what) + " settings");
  const ConfigNode id = section.child("id");
  if (!id.defined()) section.fail(std::string("missing `id` (the ") + what + " to use)");
  return id.as_string();
}

// The node of a dotted key inside a section ("policy.net_arch"), for a problem's position.
ConfigNode node_at(const ConfigNode& section, const std::string& dotted) {
  ConfigNode node = section;
  size_t start = 0;
  while (start <= dotted.size()) {
    const size_t end = std::min(dotted.find('.', start), dotted.size());
    const std::string key = dotted.substr(start, end - start);
    if (!node.has(key)) return node.child(key);  // absent: the message names the section
    node = node.child(key);
    start = end + 1;
  }
  return node;
}

void report(Problems& problems, const ConfigNode& section, const ConfigProblems& found) {
  for (const ConfigProblem& p : found) {
    const ConfigNode at = node_at(section, p.key);
    problems.attempt([&] {
      if (at.defined()) at.fail(p.message);
      section.fail(p.key + ": " + p.message);
    });
  }
}

void parse_env(const ConfigNode& env, const Registry& registry, const ParseOptions& options,
               Experiment& exp, Problems& problems) {
  if (!problems.attempt([&] { exp.env.id = required_id(env, "environment"); })) return;
  exp.env.where = env.child("id").where();
  // rlrun 0.1 wrote `max_episode_steps: 0` for envs without a registered limit; that still
  // means "none" there, and is refused everywhere else (0 would silently remove a limit).
  const EnvEntry* registered = registry.find_env(exp.env.id);
  const ConfigNode limit = env.child("max_episode_steps");
  const bool legacy_zero = registered && registered->max_episode_steps == 0 && limit.is_scalar() &&
                           limit.yaml().Scalar() == "0";
  problems.attempt([&] {
    ConfigNode section = legacy_zero ? env.without("max_episode_steps") : env;
    // The interpreter of an env never built runs nothing: not read, so not vouched for.
    if (options.env_not_built) section = section.without("python");
    exp.env.section = read_config<EnvSectionConfig>(section, {"id", "kwargs", "wrappers"});
  });
  problems.attempt([&] {
    if (options.env_not_built) {
      // Kept as written: nothing is built from them (ParseOptions).
      const ConfigNode kwargs = env.child("kwargs");
      if (kwargs.defined() && !kwargs.is_map()) kwargs.fail("expected a map of the env's settings");
      YAML::Node copy =
          kwargs.defined() ? YAML::Clone(kwargs.yaml()) : YAML::Node(YAML::NodeType::Map);
      exp.env.kwargs = AnyConfig::of_yaml(copy, copy);
      return;
    }
    const EnvEntry* entry = registry.find_env(exp.env.id);
    if (!entry && !exp.plugins.empty() && !env.trusted())
      env.child("id").fail("env '" + exp.env.id + "' comes from a plugin library named in " +
                           env.origin() +
                           "; rlrun loads no library named in a file it does "
                           "not trust (docs/security.md). If you trust it, pass --plugin " +
                           exp.plugins.front() + "." + trust_alternative(env));
    const EnvEntry& found = registry.env(exp.env.id, env.child("id"));
    if (found.runs_named_code)
      require_vouched(env.child("id"),
                      "an env that runs the Python code it names (interpreter: env.python " +
                          exp.env.section.python.value + ")",
                      exp.env.id);
    exp.env.kwargs = found.parse(env.child("kwargs"));
  });
  const ConfigNode wrappers = env.child("wrappers");
  if (!wrappers.defined()) return;
  if (!wrappers.is_sequence()) {
    problems.attempt([&] { wrappers.fail("expected a list of {id: ..., <params>}"); });
    return;
  }
  for (std::size_t i = 0; i < wrappers.size(); ++i) {
    const ConfigNode w = wrappers.at(i);
    problems.attempt([&] {
      const std::string id = required_id(w, "wrapper");
      exp.env.wrappers.push_back({id, registry.wrapper(id, w.child("id")).parse(w)});
    });
  }
}

void parse_callbacks(const ConfigNode& root, Experiment& exp, Problems& problems) {
  const ConfigNode eval = root.child("eval");
  if (problems.attempt([&] { exp.eval = read_config<EvalConfig>(eval); })) {
    exp.eval.best_metric_where = eval.child("best_metric").where();
    for (const char* rule : {"reward_threshold", "max_no_improvement_evals"})
      if (exp.eval.freq == 0 && eval.child(rule).defined())
        problems.attempt([&] {
          eval.child(rule).fail(std::string(rule) +
                                " acts after evaluations: set eval.freq > 0 too");
        });
  }
  problems.attempt(
      [&] { exp.checkpoint = read_config<CheckpointConfig>(root.child("checkpoint")); });
  problems.attempt([&] { exp.self_play = read_config<SelfPlayConfig>(root.child("self_play")); });
  const ConfigNode obs_log = root.child("obs_log");
  if (problems.attempt([&] { exp.obs_log = read_config<ObsLogConfig>(obs_log); }) &&
      exp.obs_log.env >= exp.env.section.n_envs)
    problems.attempt([&] {
      obs_log.child("env").fail("must be a training env index, 0.." +
                                std::to_string(exp.env.section.n_envs - 1));
    });
  const ConfigNode video = root.child("video");
  if (problems.attempt([&] { exp.video = read_config<VideoConfig>(video); })) {
    if ((exp.video.width == 0) != (exp.video.height == 0))
      problems.attempt(
          [&] { video.fail("set both width and height, or neither (the env's own size)"); });
    else if (exp.video.width != 0)
      if (const std::string problem = check_video_size(exp.video.width, exp.video.height);
          !problem.empty())
        problems.attempt([&] { video.child("width").fail(problem); });
  }
}

// Checks that need the env's spaces: the env's own (recorded in a model file, or as its entry
// declares them: no simulator or worker starts) under the experiment's wrappers give the
// spaces the agent sees; the algorithm checks its settings against them, and the resources the
// run will take are bounded. An env whose spaces only its running worker knows (python:) is
// checked when the first one is built (make_algorithm).
void check_against_env(const ConfigNode& root, const Registry& registry,
                       const ParseOptions& options, Experiment& exp, Problems& problems) {
  const ConfigNode env = root.child("env");
  const ConfigNode algo = root.child("algo");
  problems.attempt([&] { check_open_files(exp.env.section.n_envs, env.child("n_envs")); });
  EnvPtr probe;
  if (!problems.attempt([&] {
        try {
          std::optional<EnvSpaces> spaces = options.recorded_env_spaces;
          if (!spaces) spaces = declared_env_spaces(exp.env, registry);
          if (spaces) probe = make_spaces_only_env(exp.env, registry, *spaces);
        } catch (const std::invalid_argument& e) {
          env.fail(e.what());
        } catch (const RuntimeFailure& e) {
          env.fail(e.what());
        }
      }) ||
      !probe)
    return;
  // Each agent of a multi-agent env is one env column of the shared policy (rlrun/env.hpp).
  const AlgorithmSetup setup{probe->observation_space(), probe->action_space(),
                             exp.env.section.n_envs * probe->num_agents(), exp.run.seed};
  const AlgorithmEntry& entry = registry.algorithm(exp.algo.id, algo.child("id"));
  report(problems, algo, entry.check(exp.algo.params, setup));
}

YAML::Node resolve(const Experiment& exp, const Registry& registry) {
  YAML::Node resolved_env(YAML::NodeType::Map);
  resolved_env["id"] = exp.env.id;
  for (const auto& kv : write_config(exp.env.section)) resolved_env[kv.first] = kv.second;
  const EnvEntry* entry = registry.find_env(exp.env.id);  // null only for an env not built
  const int registered_limit = entry ? entry->max_episode_steps : 0;
  if (!exp.env.section.max_episode_steps && registered_limit > 0)
    resolved_env["max_episode_steps"] = registered_limit;
  resolved_env["kwargs"] = exp.env.kwargs.resolved();
  YAML::Node wrappers(YAML::NodeType::Sequence);
  for (const WrapperSpec& w : exp.env.wrappers) {
    YAML::Node r(YAML::NodeType::Map);
    r["id"] = w.id;
    for (const auto& kv : w.params.resolved()) r[kv.first] = kv.second;
    wrappers.push_back(r);
  }
  wrappers.SetStyle(YAML::EmitterStyle::Flow);
  resolved_env["wrappers"] = wrappers;
  YAML::Node algo(YAML::NodeType::Map);
  algo["id"] = exp.algo.id;
  for (const auto& kv : exp.algo.params.resolved()) algo[kv.first] = kv.second;

  YAML::Node resolved(YAML::NodeType::Map);
  if (!exp.plugins.empty()) resolved["plugins"] = encode(exp.plugins);
  resolved["run"] = write_config(exp.run);
  resolved["env"] = resolved_env;
  resolved["algo"] = algo;
  resolved["eval"] = write_config(exp.eval);
  resolved["checkpoint"] = write_config(exp.checkpoint);
  resolved["obs_log"] = write_config(exp.obs_log);
  resolved["video"] = write_config(exp.video);
  // Only when on, so the resolved config of every other run stays as it was.
  if (exp.self_play.freq > 0) resolved["self_play"] = write_config(exp.self_play);
  return resolved;
}

}  // namespace

Experiment parse_experiment(const ConfigNode& root, const Registry& registry,
                            const ParseOptions& options) {
  if (!root.is_map())
    root.fail("an experiment file is a map with sections run, env, algo, eval, ...");
  Problems problems;
  std::string section_list;
  for (const auto& s : kSections) section_list += (section_list.empty() ? "" : ", ") + s;
  for (const auto& key : root.keys())
    if (std::find(kSections.begin(), kSections.end(), key) == kSections.end())
      problems.attempt([&] {
        root.fail_at_key(key, "unknown section '" + key + "'" + did_you_mean(key, kSections) +
                                  "; valid sections: " + section_list);
      });

  Experiment exp;
  exp.source = root.origin();
  // plugins: env libraries (runtime/components/plugin_loader.hpp). load_experiment has loaded those of
  // the user's own files into the registry; an untrusted file's list is only recorded (a model
  // file naming a library must not load it).
  const ConfigNode plugins = root.child("plugins");
  problems.attempt([&] {
    if (!plugins.defined()) return;
    decode(plugins, exp.plugins);
    // The user's own list, relative to the user's file (an accepted model's list was loaded,
    // as written, by load_accepted_plugins: runtime/io/model_trust.hpp).
    if (plugins.trusted() && !plugins.accepted_as_a_whole())
      for (std::string& path : exp.plugins)
        path = resolve_plugin_path(path, plugin_base_dir(plugins));
  });
  problems.attempt([&] { exp.run = read_config<RunConfig>(root.child("run")); });
  parse_env(root.child("env"), registry, options, exp, problems);

  const ConfigNode algo = root.child("algo");
  problems.attempt([&] {
    exp.algo.id = required_id(algo, "algorithm");
    exp.algo.where = algo.child("id").where();
    const AlgorithmEntry& entry = registry.algorithm(exp.algo.id, algo.child("id"));
    exp.env.accepted_action_spaces = entry.action_spaces;
    exp.env.algorithm_id = exp.algo.id;
    exp.algo.params = entry.parse(algo);
    const YAML::Node gamma = exp.algo.params.resolved()["gamma"];
    if (gamma.IsDefined() && gamma.IsScalar()) exp.env.algorithm_gamma = gamma.as<double>();
  });
  parse_callbacks(root, exp, problems);
  if (problems.empty()) check_against_env(root, registry, options, exp, problems);
  problems.throw_if_any();

  // The libraries the run needs (absolute paths, the env's own included even when it came
  // from --plugin), so `rlrun eval` can name them when a model file needs one.
  const EnvEntry* env_entry = registry.find_env(exp.env.id);
  const std::string env_plugin = env_entry ? env_entry->plugin : "";
  if (!env_plugin.empty() &&
      std::find(exp.plugins.begin(), exp.plugins.end(), env_plugin) == exp.plugins.end())
    exp.plugins.push_back(env_plugin);
  exp.resolved = resolve(exp, registry);
  return exp;
}

namespace {

Experiment load_experiment_root(ConfigNode root, const std::string& default_name,
                                const std::vector<std::string>& overrides, Registry& registry) {
  if (!root.is_map())
    root.fail("an experiment file is a map with sections run, env, algo, eval, ...");
  for (const auto& o : overrides) root.apply_override(o);
  // The user's own file may name plugin libraries: they are loaded before any env id is looked
  // up (never those of an untrusted file; docs/security.md).
  const ConfigNode plugins = root.child("plugins");
  if (plugins.defined() && plugins.trusted()) load_plugins_section(plugins, registry);
  const ConfigNode name = root.child("run").child("name");
  const ConfigNode run = root.child("run");
  if (!name.defined() && (!run.defined() || run.is_map())) {  // else parse_experiment says why
    if (!run.defined()) root.yaml()["run"] = YAML::Node(YAML::NodeType::Map);
    root.yaml()["run"]["name"] = default_name;
  }
  return parse_experiment(root, registry);
}

}  // namespace

Experiment load_experiment(const std::string& path, const std::vector<std::string>& overrides,
                           Registry& registry, ConfigTrust trust) {
  return load_experiment_root(ConfigNode::load_file(path, trust),
                              std::filesystem::path(path).stem().string(), overrides, registry);
}

Experiment load_experiment_text(const std::string& text, const std::string& origin,
                                const std::string& default_name,
                                const std::vector<std::string>& overrides, Registry& registry) {
  return load_experiment_root(ConfigNode::load_string(text, origin), default_name, overrides,
                              registry);
}

EnvSpec default_env_spec(const std::string& id, const Registry& registry, const std::string& origin,
                         const std::vector<std::string>& overrides) {
  if (overrides.empty()) {
    EnvSpec spec;
    spec.id = id;
    spec.where = origin;
    const ConfigNode id_node = ConfigNode::from_yaml(YAML::Node(id), origin, "env.id");
    spec.kwargs = registry.env(id, id_node).parse(ConfigNode());
    return spec;
  }
  // `--env ID --set env.python=... --set env.kwargs.x=...`: the env section those make.
  YAML::Node root(YAML::NodeType::Map);
  root["env"]["id"] = id;
  ConfigNode node = ConfigNode::from_yaml(root, origin);
  for (const std::string& o : overrides) {
    if (o.rfind("env.", 0) != 0)
      throw ConfigError(origin + ": --set " + o + ": with --env ID only env.* settings apply");
    node.apply_override(o);
  }
  Experiment exp;
  Problems problems;
  parse_env(node.child("env"), registry, ParseOptions{}, exp, problems);
  problems.throw_if_any();
  return exp.env;
}

std::string dump_yaml(const YAML::Node& node) {
  YAML::Emitter out;
  out.SetIndent(2);
  out << node;
  return std::string(out.c_str()) + "\n";
}

std::unique_ptr<Algorithm> make_algorithm(const Experiment& experiment, const Registry& registry,
                                          const AlgorithmSetup& setup) {
  const AlgorithmEntry* entry = registry.find_algorithm(experiment.algo.id);
  if (!entry)
    throw ConfigError(experiment.algo.where + ": unknown algorithm " + experiment.algo.id);
  // The checks parsing made, again: for an env whose spaces were unknown then (python:),
  // this is their first run.
  const ConfigProblems problems = entry->check(experiment.algo.params, setup);
  if (!problems.empty()) {
    std::string message;
    for (const ConfigProblem& p : problems)
      message += (message.empty() ? "" : "\n") + experiment.algo.where + ": algo." + p.key + ": " +
                 p.message;
    throw ConfigError(message);
  }
  try {
    return entry->make(experiment.algo.params, setup);
  } catch (const std::invalid_argument& e) {
    throw ConfigError(experiment.algo.where + ": algo: " + e.what());
  }
}

}  // namespace rlrun
