#include "rlrun/runtime/experiment.hpp"

#include <algorithm>
#include <filesystem>

#include "rlrun/core/config_fields.hpp"
#include "rlrun/core/errors.hpp"
#include "rlrun/runtime/env_factory.hpp"
#include "rlrun/runtime/plugin_loader.hpp"

namespace rlrun {

namespace {

std::string required_id(const ConfigNode& section, const char* what) {
  if (!section.defined()) section.fail(std::string("missing section (needs at least `id`)"));
  if (!section.is_map()) section.fail("expected a map with `id` and " + std::string(what) + " settings");
  const ConfigNode id = section.child("id");
  if (!id.defined()) section.fail(std::string("missing `id` (the ") + what + " to use)");
  return id.as_string();
}

}  // namespace

Experiment parse_experiment(const ConfigNode& root, const Registry& registry) {
  if (!root.is_map()) root.fail("an experiment file is a map with sections run, env, algo, eval, ...");
  const std::vector<std::string> sections{"run", "env", "algo", "eval", "checkpoint", "obs_log",
                                          "video", "plugins"};
  std::string section_list;
  for (const auto& s : sections) section_list += (section_list.empty() ? "" : ", ") + s;
  for (const auto& key : root.keys())
    if (std::find(sections.begin(), sections.end(), key) == sections.end())
      root.fail_at_key(key, "unknown section '" + key + "'" + did_you_mean(key, sections) +
                           "; valid sections: " + section_list);

  Experiment exp;
  exp.source = root.origin();
  // plugins: env libraries (runtime/plugin_loader.hpp), loaded before any env id is looked up.
  const std::vector<std::string> plugins = load_plugins_section(root.child("plugins"));
  exp.run = read_config<RunConfig>(root.child("run"));
  if (exp.run.total_timesteps < 1) root.child("run").child("total_timesteps").fail("must be >= 1");
  if (exp.run.log_interval && *exp.run.log_interval < 1)
    root.child("run").child("log_interval").fail("must be >= 1 (or null for the algorithm's default)");

  // env
  const ConfigNode env = root.child("env");
  exp.env.id = required_id(env, "environment");
  exp.env.id_node = env.child("id");
  exp.env.section = read_config<EnvSectionConfig>(env, {"id", "kwargs", "wrappers"});
  if (exp.env.section.n_envs < 1) env.child("n_envs").fail("must be >= 1");
  const EnvEntry& env_entry = registry.env(exp.env.id, exp.env.id_node);
  exp.env.kwargs = env.child("kwargs");
  YAML::Node resolved_env(YAML::NodeType::Map);
  resolved_env["id"] = exp.env.id;
  for (const auto& kv : write_config(exp.env.section)) resolved_env[kv.first] = kv.second;
  if (!exp.env.section.max_episode_steps) resolved_env["max_episode_steps"] = env_entry.max_episode_steps;
  resolved_env["kwargs"] = env_entry.resolve(exp.env.kwargs);
  YAML::Node resolved_wrappers(YAML::NodeType::Sequence);
  const ConfigNode wrappers = env.child("wrappers");
  if (wrappers.defined()) {
    if (!wrappers.is_sequence()) wrappers.fail("expected a list of {id: ..., <params>}");
    for (std::size_t i = 0; i < wrappers.size(); ++i) {
      const ConfigNode w = wrappers.at(i);
      const std::string id = required_id(w, "wrapper");
      const WrapperEntry& entry = registry.wrapper(id, w.child("id"));
      YAML::Node r(YAML::NodeType::Map);
      r["id"] = id;
      for (const auto& kv : entry.resolve(w)) r[kv.first] = kv.second;
      resolved_wrappers.push_back(r);
      exp.env.wrappers.push_back(w);
    }
  }
  resolved_wrappers.SetStyle(YAML::EmitterStyle::Flow);
  resolved_env["wrappers"] = resolved_wrappers;

  // algo
  const ConfigNode algo = root.child("algo");
  exp.algo_id = required_id(algo, "algorithm");
  const AlgorithmEntry& algo_entry = registry.algorithm(exp.algo_id, algo.child("id"));
  exp.env.accepted_action_spaces = algo_entry.action_spaces;
  exp.env.algorithm_id = exp.algo_id;
  exp.algo_node = algo;
  YAML::Node resolved_algo(YAML::NodeType::Map);
  resolved_algo["id"] = exp.algo_id;
  for (const auto& kv : algo_entry.resolve(algo)) resolved_algo[kv.first] = kv.second;

  exp.eval = read_config<EvalConfig>(root.child("eval"));
  if (exp.eval.freq < 0) root.child("eval").child("freq").fail("must be >= 0");
  if (exp.eval.n_episodes < 1) root.child("eval").child("n_episodes").fail("must be >= 1");
  const ConfigNode eval = root.child("eval");
  if (exp.eval.min_evals < 0) eval.child("min_evals").fail("must be >= 0");
  if (exp.eval.max_no_improvement_evals && *exp.eval.max_no_improvement_evals < 0)
    eval.child("max_no_improvement_evals").fail("must be >= 0 (or null: never stop)");
  for (const char* rule : {"reward_threshold", "max_no_improvement_evals"})
    if (exp.eval.freq == 0 && eval.child(rule).defined())
      eval.child(rule).fail(std::string(rule) + " acts after evaluations: set eval.freq > 0 too");

  const ConfigNode checkpoint = root.child("checkpoint");
  exp.checkpoint = read_config<CheckpointConfig>(checkpoint);
  if (exp.checkpoint.freq < 0) checkpoint.child("freq").fail("must be >= 0");
  if (exp.checkpoint.keep < 0) checkpoint.child("keep").fail("must be >= 0 (0 keeps all)");

  const ConfigNode obs_log = root.child("obs_log");
  exp.obs_log = read_config<ObsLogConfig>(obs_log);
  if (exp.obs_log.freq < 0) obs_log.child("freq").fail("must be >= 0");
  if (exp.obs_log.env < 0 || exp.obs_log.env >= exp.env.section.n_envs)
    obs_log.child("env").fail("must be a training env index, 0.." +
                              std::to_string(exp.env.section.n_envs - 1));

  // video (runtime/video_callback.hpp)
  const ConfigNode video = root.child("video");
  exp.video = read_config<VideoConfig>(video);
  if (exp.video.freq < 0) video.child("freq").fail("must be >= 0");
  if (exp.video.n_episodes < 1) video.child("n_episodes").fail("must be >= 1");
  if (exp.video.fps && !(*exp.video.fps > 0)) video.child("fps").fail("must be > 0 (or null)");
  if (exp.video.width < 0 || exp.video.width % 2 != 0)
    video.child("width").fail("must be 0 (the env's size) or a positive even number (H.264)");
  if (exp.video.height < 0 || exp.video.height % 2 != 0)
    video.child("height").fail("must be 0 (the env's size) or a positive even number (H.264)");
  if ((exp.video.width == 0) != (exp.video.height == 0))
    video.fail("set both width and height, or neither (the env's own size)");

  // Build one env now: bad kwargs, wrapper parameters or an action space the algorithm cannot
  // handle are reported before any run directory exists.
  try {
    make_env(exp.env, registry, "", 0.0);
  } catch (const std::invalid_argument& e) {
    env.fail(e.what());
  }

  exp.resolved = YAML::Node(YAML::NodeType::Map);
  // The libraries the run needs (absolute paths, the env's own included even when it came
  // from --plugin), so `rlrun eval` reloads them from the model file alone.
  std::vector<std::string> needed_plugins = plugins;
  const std::string env_plugin = plugin_of_env(exp.env.id);
  if (!env_plugin.empty() &&
      std::find(needed_plugins.begin(), needed_plugins.end(), env_plugin) == needed_plugins.end())
    needed_plugins.push_back(env_plugin);
  if (!needed_plugins.empty()) exp.resolved["plugins"] = encode(needed_plugins);
  exp.resolved["run"] = write_config(exp.run);
  exp.resolved["env"] = resolved_env;
  exp.resolved["algo"] = resolved_algo;
  exp.resolved["eval"] = write_config(exp.eval);
  exp.resolved["checkpoint"] = write_config(exp.checkpoint);
  exp.resolved["obs_log"] = write_config(exp.obs_log);
  exp.resolved["video"] = write_config(exp.video);
  return exp;
}

Experiment load_experiment(const std::string& path, const std::vector<std::string>& overrides,
                           const Registry& registry) {
  ConfigNode root = ConfigNode::load_file(path);
  if (!root.is_map()) root.fail("an experiment file is a map with sections run, env, algo, eval, ...");
  for (const auto& o : overrides) root.apply_override(o);
  const ConfigNode name = root.child("run").child("name");
  if (!name.defined()) {
    if (!root.yaml()["run"].IsMap()) root.yaml()["run"] = YAML::Node(YAML::NodeType::Map);
    root.yaml()["run"]["name"] = std::filesystem::path(path).stem().string();
  }
  return parse_experiment(root, registry);
}

std::string dump_yaml(const YAML::Node& node) {
  YAML::Emitter out;
  out.SetIndent(2);
  out << node;
  return std::string(out.c_str()) + "\n";
}

}  // namespace rlrun
