#include "rlrun/runtime/workflows/zoo/zoo_wrappers.hpp"

#include <algorithm>
#include <functional>

namespace rlrun::zoo {

namespace {

// One class of the list and its keyword arguments (a map node, or undefined).
struct ClassUse {
  std::string name;
  ConfigNode kwargs;
  ConfigNode at;
};

std::vector<ClassUse> class_uses(const ConfigNode& node, const std::string& what) {
  std::vector<ClassUse> uses;
  auto one = [&](const ConfigNode& item) {
    if (item.is_scalar()) {
      uses.push_back({item.as_string(), ConfigNode(), item});
    } else if (item.is_map() && item.size() == 1) {
      const std::string name = item.keys().front();
      const ConfigNode kwargs = item.child(name);
      if (kwargs.defined() && !kwargs.is_map())
        kwargs.fail(what + " " + name + ": keyword arguments are a map");
      uses.push_back({name, kwargs, item});
    } else {
      item.fail(what + " entries are a class path or {class path: {keyword: value}}");
    }
  };
  if (node.is_sequence()) {
    for (std::size_t i = 0; i < node.size(); ++i) one(node.at(i));
  } else {
    one(node);
  }
  return uses;
}

// The class name after the last dot (module paths differ between zoo versions).
std::string class_name(const std::string& path) {
  const auto dot = path.rfind('.');
  return dot == std::string::npos ? path : path.substr(dot + 1);
}

void only_kwargs(const ClassUse& use, const std::vector<std::string>& allowed) {
  if (!use.kwargs.defined()) return;
  for (const std::string& key : use.kwargs.keys())
    if (std::find(allowed.begin(), allowed.end(), key) == allowed.end())
      use.kwargs.fail_at_key(
          key, use.name + ": keyword '" + key + "' is not translated" + did_you_mean(key, allowed));
}

YAML::Node wrapper(const std::string& id) {
  YAML::Node w(YAML::NodeType::Map);
  w["id"] = id;
  return w;
}

}  // namespace

void translate_env_wrappers(const ConfigNode& env_wrapper, YAML::Node env, int registered_limit,
                            std::vector<std::string>& notes) {
  if (!env_wrapper.defined()) return;  // `env_wrapper: null`: none (get_wrapper_class)
  for (const ClassUse& use : class_uses(env_wrapper, "env_wrapper")) {
    const std::string name = class_name(use.name);
    if (name == "TimeLimit") {
      // Applied above gym.make's own TimeLimit: the shorter limit ends episodes.
      only_kwargs(use, {"max_episode_steps"});
      if (!use.kwargs.has("max_episode_steps")) use.at.fail(use.name + " needs max_episode_steps");
      const int64_t steps = use.kwargs.child("max_episode_steps").as_int();
      if (steps < 1) use.kwargs.child("max_episode_steps").fail("must be >= 1");
      const int64_t limit =
          registered_limit > 0 ? std::min<int64_t>(steps, registered_limit) : steps;
      env["max_episode_steps"] = limit;
      if (limit != steps)
        notes.push_back(use.name + "(max_episode_steps=" + std::to_string(steps) +
                        ") wraps the registered limit of " + std::to_string(registered_limit) +
                        ", which ends episodes first");
    } else if (name == "TimeFeatureWrapper") {
      only_kwargs(use, {"max_steps", "test_mode"});
      YAML::Node w = wrapper("TimeFeature");
      if (use.kwargs.has("max_steps")) w["max_steps"] = use.kwargs.child("max_steps").yaml();
      if (use.kwargs.has("test_mode")) w["test_mode"] = use.kwargs.child("test_mode").yaml();
      env["wrappers"].push_back(w);
    } else if (name == "ClipAction") {
      only_kwargs(use, {});
      env["wrappers"].push_back(wrapper("ClipAction"));
    } else if (name == "RescaleAction") {
      only_kwargs(use, {"min_action", "max_action"});
      YAML::Node w = wrapper("RescaleAction");
      for (const char* key : {"min_action", "max_action"})
        if (use.kwargs.has(key)) w[key] = use.kwargs.child(key).yaml();
      env["wrappers"].push_back(w);
    } else {
      use.at.fail("env_wrapper " + use.name +
                  ": rlrun translates TimeLimit, TimeFeatureWrapper, "
                  "ClipAction and RescaleAction (docs/zoo.md); add an rlrun wrapper to "
                  "env.wrappers by hand for others");
    }
  }
  if (env["wrappers"]) env["wrappers"].SetStyle(YAML::EmitterStyle::Flow);
}

void translate_callbacks(const ConfigNode& callback, YAML::Node& experiment, int n_envs,
                         std::vector<std::string>& notes) {
  if (!callback.defined()) return;
  for (const ClassUse& use : class_uses(callback, "callback")) {
    const std::string name = class_name(use.name);
    if (name == "CheckpointCallback") {
      // SB3 counts save_freq in callback calls (one per VecEnv step); rlrun in total env steps.
      only_kwargs(use, {"save_freq", "save_path", "name_prefix", "verbose"});
      if (!use.kwargs.has("save_freq")) use.at.fail(use.name + " needs save_freq");
      experiment["checkpoint"]["freq"] = use.kwargs.child("save_freq").as_int() * n_envs;
      for (const char* ignored : {"save_path", "name_prefix", "verbose"})
        if (use.kwargs.has(ignored))
          notes.push_back(use.name + " " + ignored +
                          ": rlrun writes checkpoints to the run "
                          "directory's checkpoints/");
    } else {
      use.at.fail("callback " + use.name +
                  ": rlrun has no such callback (it translates "
                  "CheckpointCallback; evaluation is the eval section)");
    }
  }
}

}  // namespace rlrun::zoo
