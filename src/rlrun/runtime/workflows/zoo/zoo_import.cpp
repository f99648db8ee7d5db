#include "rlrun/runtime/workflows/zoo/zoo_import.hpp"
#include "rlrun/core/ascii_lower.hpp"

#include <algorithm>
#include <cctype>
#include <functional>
#include <utility>

#include "rlrun/core/errors.hpp"
#include "rlrun/core/quoted_text.hpp"
#include "rlrun/runtime/workflows/zoo/zoo_policy.hpp"
#include "rlrun/runtime/workflows/zoo/zoo_values.hpp"
#include "rlrun/runtime/workflows/zoo/zoo_wrappers.hpp"

namespace rlrun::zoo {

namespace {

// rl-zoo's defaults for what the hyperparameter file does not say (rl_zoo3/train.py): an
// evaluation every 25000 env steps (--eval-freq, divided by n_envs into callback calls, so
// counted in total steps as rlrun's eval.freq is) of 5 episodes (--eval-episodes), with the
// deterministic policy (ExperimentManager.deterministic_eval: all but Atari).
constexpr int64_t kZooEvalFreq = 25000;
constexpr int kZooEvalEpisodes = 5;

// Keys of the zoo's VecNormalize kwargs that env.normalize has.
const std::vector<std::string> kNormalizeKeys{"norm_obs",    "norm_reward", "clip_obs",
                                              "clip_reward", "gamma",       "epsilon"};

// Collects every problem (one line each) so one import shows them all.
class Problems {
 public:
  void attempt(const std::function<void()>& step) {
    try {
      step();
    } catch (const ConfigError& e) {
      lines_ += (lines_.empty() ? "" : "\n") + std::string(e.what());
    }
  }
  void throw_if_any() const {
    if (!lines_.empty()) throw ConfigError(lines_);
  }

 private:
  std::string lines_;
};

// The algorithm's top-level keys: a nested section's rows ("policy.net_arch") count as "policy".
std::vector<std::string> keys_of(const std::vector<FieldDoc>& rows) {
  std::vector<std::string> keys;
  for (const FieldDoc& row : rows) {
    const std::string key = row.key.substr(0, row.key.find('.'));
    if (std::find(keys.begin(), keys.end(), key) == keys.end()) keys.push_back(key);
  }
  return keys;
}

// The keys of the algorithm's `policy` section (its rows "policy.<key>").
std::vector<std::string> policy_keys(const std::vector<FieldDoc>& rows) {
  const std::string prefix = "policy.";
  std::vector<std::string> keys;
  for (const FieldDoc& row : rows)
    if (row.key.starts_with(prefix)) keys.push_back(row.key.substr(prefix.size()));
  return keys;
}

// Run names are one path component of at most 200 characters (RelativeName); an env id's
// part is kept well below.
constexpr std::size_t kMaxRunNameEnvChars = 100;

class Translation {
 public:
  Translation(const ZooEntry& entry, const Registry& registry) : entry_(entry) {
    const AlgorithmEntry* algo = registry.find_algorithm(entry.algorithm);
    if (!algo) throw ConfigError(entry.file + ": rlrun has no algorithm " + entry.algorithm);
    const std::vector<FieldDoc> rows = algo->params();
    algo_keys_ = keys_of(rows);
    policy_keys_ = policy_keys(rows);
    if (const EnvEntry* env = registry.find_env(entry.env_id))
      registered_limit_ = env->max_episode_steps;
  }

  ZooImport run() {
    ZooImport out;
    out.source = entry_;
    YAML::Node& x = out.experiment;
    x["run"]["name"] = zoo_run_name(entry_.algorithm, entry_.env_id);
    x["env"]["id"] = entry_.env_id;
    x["algo"]["id"] = entry_.algorithm;
    const ConfigNode& e = entry_.node;
    const std::vector<std::string> keys = e.keys();
    Problems problems;
    auto has = [&](const char* key) { return e.has(key); };
    if (!has("n_timesteps"))
      problems.attempt([&] { e.fail("the entry has no n_timesteps (rl-zoo requires it)"); });
    const int n_envs = has("n_envs") ? static_cast<int>(e.child("n_envs").as_int()) : 1;
    for (const std::string& key : keys)
      problems.attempt([&] { translate(key, e.child(key), x, out.notes, n_envs); });
    problems.throw_if_any();
    x["eval"]["freq"] = kZooEvalFreq;
    x["eval"]["n_episodes"] = kZooEvalEpisodes;
    x["eval"]["deterministic"] = true;
    if (cnn_policy_ && !policy_["net_arch"].IsDefined()) cnn_default_net_arch();
    if (!policy_.IsNull() && policy_.size() > 0) {
      policy_.SetStyle(YAML::EmitterStyle::Flow);
      x["algo"]["policy"] = policy_;
    }
    return out;
  }

 private:
  // SB3's net_arch for a CnnPolicy that sets none: ActorCriticPolicy's, DQNPolicy's and
  // QRDQNPolicy's heads have no hidden layer ([]); TD3Policy's (DDPG's too) [256, 256] instead of its MLP default
  // [400, 300]; SACPolicy and TQCPolicy keep [256, 256], rlrun's default for them too.
  void cnn_default_net_arch() {
    const std::string& algo = entry_.algorithm;
    if (algo == "PPO" || algo == "MaskablePPO" || algo == "A2C" || algo == "DQN" ||
        algo == "QRDQN") {
      policy_["net_arch"] = YAML::Node(YAML::NodeType::Sequence);
    } else if (algo == "TD3" || algo == "DDPG") {
      YAML::Node layers(YAML::NodeType::Sequence);
      layers.push_back(256);
      layers.push_back(256);
      layers.SetStyle(YAML::EmitterStyle::Flow);
      policy_["net_arch"] = layers;
    }
  }

  void translate(const std::string& key, const ConfigNode& value, YAML::Node& x,
                 std::vector<std::string>& notes, int n_envs) {
    const ConfigNode& e = entry_.node;
    if (key == "n_timesteps") {
      value.as_int();  // an integer, possibly written 1e5 / !!float 1e5
      x["run"]["total_timesteps"] = value.yaml();
    } else if (key == "n_envs") {
      x["env"]["n_envs"] = value.yaml();
    } else if (key == "policy" && entry_.algorithm == "ARS" &&
               value.as_string() == "LinearPolicy") {
      // sb3-contrib's ARSLinearPolicy: ARSPolicy with net_arch [], no bias, no tanh.
      policy_["net_arch"] = YAML::Node(YAML::NodeType::Sequence);
      policy_["with_bias"] = false;
      policy_["squash_output"] = false;
    } else if (key == "policy") {
      if (check_policy_name(value, entry_.algorithm)) {
        policy_["features_extractor_class"] = "NatureCNN";
        cnn_policy_ = true;
      }
    } else if (key == "policy_kwargs") {
      if (!value.defined()) return;
      const YAML::Node policy =
          translate_policy_kwargs(value, policy_keys_, entry_.algorithm, notes);
      for (const auto& kv : policy) policy_[kv.first.Scalar()] = kv.second;
    } else if (key == "replay_buffer_kwargs") {
      replay_buffer_kwargs(key, value, x);
    } else if (key == "normalize") {
      x["env"]["normalize"] = normalize(value);
    } else if (key == "frame_stack") {
      // Only observation normalisation cares about the order (reward normalisation, as on the
      // zoo's CarRacing entry, does not).
      if (e.has("normalize") && normalizes_observations(e.child("normalize")))
        value.fail(
            "frame_stack with normalize: rl-zoo stacks normalised observations "
            "(VecFrameStack outside VecNormalize) while rlrun's FrameStack wrapper sits "
            "inside env.normalize; not translated");
      YAML::Node w(YAML::NodeType::Map);
      w["id"] = "FrameStack";
      w["n_stack"] = value.yaml();
      w["layout"] = "sb3";                // VecFrameStack: images stack on their channel axis
      x["env"]["wrappers"].push_back(w);  // rl-zoo's VecFrameStack pads with zeros, as FrameStack
    } else if (key == "env_wrapper") {
      translate_env_wrappers(value, x["env"], registered_limit_, notes);
    } else if (key == "callback") {
      translate_callbacks(value, x, n_envs, notes);
    } else if (key == "env_kwargs") {
      if (value.defined()) x["env"]["kwargs"] = value.yaml();
    } else if (key == "noise_type") {
      if (!value.defined()) return;
      // rl-zoo tests `"normal" in noise_type` after strip(); its files write the exact names.
      const std::string type = value.as_string();
      if (type != "normal" && type != "ornstein-uhlenbeck")
        value.fail("noise_type '" + type + "': rl-zoo knows normal and ornstein-uhlenbeck");
      if (!e.has("noise_std")) value.fail("noise_type needs noise_std (rl-zoo reads both)");
      algo_param(key, value, x);
    } else if (key == "n_episodes_rollout") {
      // SB3 < 0.11: train_freq=-1 with n_episodes_rollout=N collected N episodes per update,
      // which is train_freq [N, episode] since.
      const int64_t episodes = value.as_int();
      if (episodes <= 0) return;  // -1: train_freq (in steps) decides
      if (e.has("train_freq") && e.child("train_freq").is_scalar() &&
          e.child("train_freq").as_int() > 0)
        value.fail("n_episodes_rollout and a positive train_freq: SB3 refused both at once");
      YAML::Node freq(YAML::NodeType::Sequence);
      freq.push_back(episodes);
      freq.push_back("episode");
      freq.SetStyle(YAML::EmitterStyle::Flow);
      x["algo"]["train_freq"] = freq;
      notes.push_back("n_episodes_rollout: " + std::to_string(episodes) +
                      " (SB3 < 0.11) is train_freq [" + std::to_string(episodes) + ", episode]");
    } else if (key == "train_freq") {
      if (value.is_scalar() && value.as_int() == -1 && e.has("n_episodes_rollout")) return;
      algo_param(key, value, x);
    } else {
      algo_param(key, value, x);
    }
  }

  // rl-zoo writes the replay buffer's options as a Python dict string.
  void replay_buffer_kwargs(const std::string& key, const ConfigNode& value, YAML::Node& x) {
    if (!value.defined()) return;
    const PyValue kwargs = python_value(value, "replay_buffer_kwargs");
    if (kwargs.kind != PyValue::Kind::kDict)
      value.fail("replay_buffer_kwargs must be a dict, found " + kwargs.describe());
    algo_param(key, value, x);
    // SB3's ReplayBuffer takes handle_timeout_termination among these kwargs (the zoo's atari
    // entries say to turn it off for optimize_memory_usage); rlrun has it on the algorithm.
    YAML::Node translated = to_yaml(kwargs);
    const std::string timeouts = "handle_timeout_termination";
    if (const YAML::Node found = std::as_const(translated)[timeouts]) {
      x["algo"][timeouts] = YAML::Clone(found);
      translated.remove(timeouts);
    }
    if (translated.size() > 0)
      x["algo"][key] = translated;
    else
      x["algo"].remove(key);
  }

  void algo_param(const std::string& key, const ConfigNode& value, YAML::Node& x) {
    if (key == "policy") return;
    if (std::find(algo_keys_.begin(), algo_keys_.end(), key) == algo_keys_.end())
      entry_.node.fail_at_key(key, "rlrun's " + entry_.algorithm + " has no hyperparameter '" +
                                       quoted_text(key) + "'" + did_you_mean(key, algo_keys_) +
                                       " (see `rlrun list " + entry_.algorithm + "`)");
    x["algo"][key] = value.yaml();
  }

  // `normalize: true`, a Python dict string, or a YAML map -> env.normalize. rl-zoo gives
  // VecNormalize the algorithm's gamma when the entry sets one; otherwise VecNormalize's 0.99,
  // which is every rlrun algorithm's default gamma: `gamma: null` says both.
  YAML::Node normalize(const ConfigNode& value) {
    if (value.is_scalar()) {
      bool on = false;
      if (YAML::convert<bool>::decode(value.yaml(), on)) return YAML::Node(on);
    }
    const PyValue kwargs = python_value(value, "normalize");
    if (kwargs.kind != PyValue::Kind::kDict)
      value.fail("normalize must be true/false or a dict of VecNormalize arguments, found " +
                 kwargs.describe());
    YAML::Node map(YAML::NodeType::Map);
    for (const auto& [key, item] : kwargs.entries) {
      if (std::find(kNormalizeKeys.begin(), kNormalizeKeys.end(), key) == kNormalizeKeys.end())
        value.fail("normalize key '" + key + "': env.normalize has " + join(kNormalizeKeys) +
                   did_you_mean(key, kNormalizeKeys));
      if (key == "gamma" && entry_.node.has("gamma")) continue;  // the zoo overrides it
      map[key] = to_yaml(item);
    }
    map.SetStyle(YAML::EmitterStyle::Flow);
    return map;
  }

  // VecNormalize's norm_obs (true unless the zoo's dict says otherwise).
  bool normalizes_observations(const ConfigNode& value) {
    const YAML::Node n = normalize(value);
    if (n.IsScalar()) return n.as<bool>();  // normalize() only returns a decoded bool
    if (!n["norm_obs"]) return true;
    bool on = true;
    if (!YAML::convert<bool>::decode(n["norm_obs"], on))
      value.fail("normalize norm_obs must be True or False");
    return on;
  }

  static std::string join(const std::vector<std::string>& v) {
    std::string s;
    for (const auto& x : v) s += (s.empty() ? "" : ", ") + x;
    return s;
  }

  const ZooEntry& entry_;
  std::vector<std::string> algo_keys_, policy_keys_;
  int registered_limit_ = 0;
  YAML::Node policy_{YAML::NodeType::Map};
  bool cnn_policy_ = false;  // policy: CnnPolicy
};

}  // namespace

std::string zoo_run_name(const std::string& algorithm, const std::string& env_id) {
  std::string name = ascii_lower(algorithm) + "_";
  for (const char c : env_id.substr(0, kMaxRunNameEnvChars))
    name +=
        std::isalnum(static_cast<unsigned char>(c)) || c == '.' || c == '_' || c == '-' ? c : '-';
  return name;
}

ZooImport translate_zoo_entry(const ZooEntry& entry, const Registry& registry) {
  try {
    return Translation(entry, registry).run();
  } catch (const ConfigError& e) {
    throw ConfigError(bounded_message(e.what()));
  }
}

Experiment check_zoo_experiment(ZooImport& imported, const std::vector<std::string>& overrides,
                                const Registry& registry) {
  // The zoo file's values are untrusted; the env id is the one the user named.
  ConfigNode root =
      ConfigNode::from_yaml(imported.experiment, imported.source.file, "", ConfigTrust::kUntrusted);
  root.vouch_for("env.id",
                 "the env id " + quoted_text(imported.source.env_id) + " on the command line");
  for (const std::string& o : overrides) root.apply_override(o);
  imported.overrides = overrides;
  try {
    return parse_experiment(root, registry);
  } catch (const ConfigError& e) {
    throw ConfigError(bounded_message(e.what()));
  } catch (const RuntimeFailure& e) {
    throw RuntimeFailure(bounded_message(e.what()));
  }
}

Experiment load_zoo_experiment(const std::string& path, const std::string& env_id,
                               const std::string& algorithm,
                               const std::vector<std::string>& overrides, const Registry& registry,
                               const std::string& entry_name) {
  ZooImport imported =
      translate_zoo_entry(read_zoo_entry(path, env_id, algorithm, entry_name), registry);
  return check_zoo_experiment(imported, overrides, registry);
}

}  // namespace rlrun::zoo
