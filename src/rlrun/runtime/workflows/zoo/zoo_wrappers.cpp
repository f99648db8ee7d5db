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

// A wrapper with one parameter.
template <class T>
YAML::Node wrapper(const std::string& id, const char* key, const T& value) {
  YAML::Node w = wrapper(id);
  w[key] = value;
  return w;
}

int64_t int_kwarg(const ClassUse& use, const char* key, int64_t fallback) {
  return use.kwargs.has(key) ? use.kwargs.child(key).as_int() : fallback;
}

bool bool_kwarg(const ClassUse& use, const char* key, bool fallback) {
  return use.kwargs.has(key) ? use.kwargs.child(key).as_bool() : fallback;
}

// SB3's WarpFrame: cv2 gray, then cv2.resize(INTER_AREA) to height x width, a channel axis of 1.
void warp_frame(YAML::Node env, int64_t height, int64_t width) {
  YAML::Node gray = wrapper("GrayscaleObservation");
  gray["keep_dim"] = true;
  gray["weights"] = "opencv";
  env["wrappers"].push_back(gray);
  YAML::Node resize = wrapper("ResizeObservation");
  resize["shape"].push_back(height);
  resize["shape"].push_back(width);
  env["wrappers"].push_back(resize);
}

// SB3's AtariWrapper (atari_wrappers.py) in its order: NoopReset, MaxAndSkip, (EpisodicLife,
// FireReset: Atari's lives and FIRE button, which other envs lack), WarpFrame, ClipReward.
void atari_wrapper(const ClassUse& use, YAML::Node env, std::vector<std::string>& notes) {
  only_kwargs(use, {"noop_max", "frame_skip", "screen_size", "terminal_on_life_loss", "clip_reward",
                    "action_repeat_probability"});
  if (use.kwargs.has("action_repeat_probability") &&
      use.kwargs.child("action_repeat_probability").as_double() > 0.0)
    use.kwargs.child("action_repeat_probability")
        .fail("sticky actions (StickyActionEnv) are not translated");
  if (const int64_t noop_max = int_kwarg(use, "noop_max", 30); noop_max > 0) {
    env["wrappers"].push_back(wrapper("NoopReset", "noop_max", noop_max));
  }
  if (const int64_t skip = int_kwarg(use, "frame_skip", 4); skip > 1) {
    env["wrappers"].push_back(wrapper("MaxAndSkip", "skip", skip));
  }
  if (bool_kwarg(use, "terminal_on_life_loss", true))
    notes.push_back(use.name +
                    " terminal_on_life_loss: only Atari games have lives (EpisodicLifeEnv); "
                    "rlrun's envs end episodes themselves");
  const int64_t size = int_kwarg(use, "screen_size", 84);
  warp_frame(env, size, size);
  if (bool_kwarg(use, "clip_reward", true))
    env["wrappers"].push_back(wrapper("TransformReward", "sign", true));
}

// The image wrappers and SB3's Atari pieces; false when `name` is none of them.
bool translate_image_wrapper(const std::string& name, const ClassUse& use, YAML::Node env,
                             std::vector<std::string>& notes) {
  if (name == "ResizeObservation" || name == "YAMLCompatResizeObservation") {
    // Gymnasium 0.29 takes one number or a pair, 1.0 a tuple, which the current zoo passes
    // through rl_zoo3.wrappers.YAMLCompatResizeObservation as a list.
    only_kwargs(use, {"shape"});
    if (!use.kwargs.has("shape")) use.at.fail(use.name + " needs shape");
    env["wrappers"].push_back(
        wrapper("ResizeObservation", "shape", use.kwargs.child("shape").yaml()));
  } else if (name == "GrayScaleObservation" || name == "GrayscaleObservation") {
    // Gymnasium 0.29's GrayScaleObservation (the zoo's path) calls OpenCV; 1.0's
    // GrayscaleObservation weighs in float.
    only_kwargs(use, {"keep_dim"});
    YAML::Node w = wrapper("GrayscaleObservation");
    w["keep_dim"] = bool_kwarg(use, "keep_dim", false);
    w["weights"] = name == "GrayScaleObservation" ? "opencv" : "gymnasium";
    env["wrappers"].push_back(w);
  } else if (name == "FrameSkip" || name == "MaxAndSkipEnv") {
    only_kwargs(use, {"skip"});
    env["wrappers"].push_back(wrapper(name == "FrameSkip" ? "FrameSkip" : "MaxAndSkip", "skip",
                                      int_kwarg(use, "skip", 4)));
  } else if (name == "NoopResetEnv") {
    only_kwargs(use, {"noop_max"});
    env["wrappers"].push_back(wrapper("NoopReset", "noop_max", int_kwarg(use, "noop_max", 30)));
  } else if (name == "ClipRewardEnv") {
    only_kwargs(use, {});
    env["wrappers"].push_back(wrapper("TransformReward", "sign", true));
  } else if (name == "WarpFrame") {
    only_kwargs(use, {"width", "height"});
    warp_frame(env, int_kwarg(use, "height", 84), int_kwarg(use, "width", 84));
  } else if (name == "AtariWrapper") {
    atari_wrapper(use, env, notes);
  } else {
    return false;
  }
  return true;
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
    } else if (!translate_image_wrapper(name, use, env, notes)) {
      use.at.fail("env_wrapper " + use.name +
                  ": rlrun translates TimeLimit, TimeFeatureWrapper, ClipAction, RescaleAction, "
                  "ResizeObservation, GrayScaleObservation, FrameSkip, AtariWrapper and its "
                  "pieces (docs/zoo.md); add an rlrun wrapper to env.wrappers by hand for others");
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
