#include "rlrun/runtime/workflows/zoo/zoo_file.hpp"
#include "rlrun/core/ascii_lower.hpp"

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <utility>
#include <vector>

#include "rlrun/core/errors.hpp"
#include "rlrun/core/quoted_text.hpp"

namespace rlrun::zoo {

namespace {

// rl-zoo's algorithm names (rl_zoo3/utils.py ALGOS) that rlrun implements.
const std::vector<std::pair<std::string, std::string>> kAlgorithms{
    {"ppo", "PPO"},   {"a2c", "A2C"},   {"dqn", "DQN"},      {"sac", "SAC"},
    {"td3", "TD3"},   {"ddpg", "DDPG"}, {"tqc", "TQC"},      {"qrdqn", "QRDQN"},
    {"trpo", "TRPO"}, {"ars", "ARS"},   {"crossq", "CrossQ"}};
// sb3-contrib's MaskablePPO and RecurrentPPO under rl-zoo's names (rl_zoo3/utils.py
// ALGOS["ppo_mask"], ALGOS["ppo_lstm"]) and their own, compared without '-' and '_' as
// kNotInRlrun's names are.
const std::vector<std::pair<std::string, std::string>> kContribPPONames{
    {"ppomask", "MaskablePPO"},
    {"maskableppo", "MaskablePPO"},
    {"ppolstm", "RecurrentPPO"},
    {"recurrentppo", "RecurrentPPO"}};

// The algorithms of rl-zoo 2.4's files (rl_zoo3/utils.py ALGOS, from sb3-contrib) and of
// sb3-contrib that rlrun does not have, by the names a file or --algo gives them (lower case,
// without '-' and '_': qrdqn.yml, ppo_lstm.yml, --algo qr-dqn), and what to say.
const std::vector<std::pair<std::string, std::string>> kNotInRlrun{
    // rl-zoo keeps its her.yml from before SB3 1.1 for reference (entries with model_class).
    {"her",
     "rl-zoo's her.yml predates SB3 1.1, where HER became a replay buffer "
     "(replay_buffer_class: HerReplayBuffer) in each algorithm's own file: import the "
     "entry from tqc.yml, sac.yml, ..."}};

const char* const kImported =
    "rlrun imports zoo files of ppo, ppo_mask, ppo_lstm, a2c, dqn, qrdqn, trpo, ars, sac, td3, "
    "ddpg, tqc and crossq";

// Env ids whose zoo entries were renamed with Gymnasium's versions: {old, new}. The MuJoCo
// tasks' v2 and v3 ids run on mujoco-py, which Gymnasium 1.0 still registers but nobody can
// install any more; v4 is the same task on MuJoCo's own bindings (gymnasium/envs/mujoco/*_v4.py:
// "v4: all mujoco environments now use the mujoco bindings"), and the zoo keeps some entries
// (InvertedPendulum, Reacher, HumanoidStandup, ...) under v2 only.
const std::vector<std::pair<std::string, std::string>> kRenamed{
    {"LunarLander-v2", "LunarLander-v3"},
    {"LunarLanderContinuous-v2", "LunarLanderContinuous-v3"},
    {"LunarLanderNoVel-v2", "LunarLanderNoVel-v3"},  // ppo_lstm.yml's names
    {"LunarLanderContinuousNoVel-v2", "LunarLanderContinuousNoVel-v3"},
    {"Ant-v2", "Ant-v4"},
    {"Ant-v3", "Ant-v4"},
    {"HalfCheetah-v2", "HalfCheetah-v4"},
    {"HalfCheetah-v3", "HalfCheetah-v4"},
    {"Hopper-v2", "Hopper-v4"},
    {"Hopper-v3", "Hopper-v4"},
    {"Humanoid-v2", "Humanoid-v4"},
    {"Humanoid-v3", "Humanoid-v4"},
    {"HumanoidStandup-v2", "HumanoidStandup-v4"},
    {"InvertedDoublePendulum-v2", "InvertedDoublePendulum-v4"},
    {"InvertedPendulum-v2", "InvertedPendulum-v4"},
    {"Pusher-v2", "Pusher-v4"},
    {"Reacher-v2", "Reacher-v4"},
    {"Swimmer-v2", "Swimmer-v4"},
    {"Swimmer-v3", "Swimmer-v4"},
    {"Walker2d-v2", "Walker2d-v4"},
    {"Walker2d-v3", "Walker2d-v4"}};

// rlrun's Gymnasium env family: `gymnasium:LunarLander-v3` is gymnasium.make("LunarLander-v3"),
// and the zoo keys its entries by that id.
constexpr std::string_view kGymnasiumPrefix = "gymnasium:";

// A zoo entry nests a few levels (entry, env_wrapper list, {class: kwargs}, kwargs, value) and
// takes a few hundred bytes. Anything far beyond is refused before the translation walks or
// copies it; aliases count each time they repeat a value (the translation copies them).
constexpr int kMaxEntryDepth = 16;
constexpr std::size_t kMaxEntryBytes = 64 * 1024;
constexpr std::size_t kMaxEntryValues = 10000;

// The rlrun algorithm named `name` (a file stem or --algo), "" for none.
std::string rlrun_algorithm(const std::string& name) {
  const std::string wanted = ascii_lower(name);
  for (const auto& [zoo, rlrun] : kAlgorithms)
    if (wanted == zoo) return rlrun;
  std::string key;
  for (const char c : wanted)
    if (c != '-' && c != '_') key += c;
  for (const auto& [name, algorithm] : kContribPPONames)
    if (key == name) return algorithm;
  return "";
}

// What to say when `name` is an algorithm rlrun does not have (kNotInRlrun), else "".
std::string missing_algorithm(const std::string& name) {
  std::string key;
  for (const char c : ascii_lower(name))
    if (c != '-' && c != '_') key += c;
  for (const auto& [known, description] : kNotInRlrun)
    if (key == known) return description;
  return "";
}

std::string at(const std::string& file, const YAML::Mark& mark) {
  return file + ":" + std::to_string(mark.line + 1) + ":" + std::to_string(mark.column + 1);
}

// The text of a scalar of the entry. A YAML file is Unicode; yaml-cpp reads any bytes, but
// its emitter would write a stray one as U+FFFD, so the written experiment would differ.
const std::string& utf8_text(const ZooEntry& entry, const YAML::Node& scalar) {
  if (!valid_utf8(scalar.Scalar()))
    throw ConfigError(at(entry.file, scalar.Mark()) + ": not UTF-8 text (YAML files are Unicode)");
  return scalar.Scalar();
}

// Refuses an entry nested deeper than kMaxEntryDepth, larger than kMaxEntryBytes of text or
// kMaxEntryValues values, or with text that is not UTF-8. The walk is bounded: the loader counted the file's nodes with aliases
// expanded (kMaxConfigNodes).
void check_entry_size(const ZooEntry& entry) {
  std::size_t bytes = 0, values = 0;
  std::vector<std::pair<YAML::Node, int>> stack{{entry.node.yaml(), 1}};
  while (!stack.empty()) {
    const auto [node, depth] = stack.back();
    stack.pop_back();
    if (depth > kMaxEntryDepth)
      throw ConfigError(at(entry.file, node.Mark()) + ": entry '" + quoted_text(entry.entry_name) +
                        "' nests deeper than " + std::to_string(kMaxEntryDepth) +
                        " levels; a zoo entry has about five");
    if (node.IsScalar()) bytes += utf8_text(entry, node).size();
    for (const auto& item : node) {
      if (node.IsMap()) {
        bytes += utf8_text(entry, item.first).size();
        stack.emplace_back(item.second, depth + 1);
      } else {
        stack.emplace_back(item, depth + 1);
      }
    }
    if (bytes > kMaxEntryBytes || ++values > kMaxEntryValues)
      throw ConfigError(entry.file + ": entry '" + quoted_text(entry.entry_name) +
                        "' holds more than " + std::to_string(kMaxEntryBytes / 1024) +
                        " KiB of text or " + std::to_string(kMaxEntryValues) +
                        " values with its aliases expanded; a zoo entry takes a few hundred "
                        "bytes");
  }
}

// The entry names to try for `env_id`, in order, and the env to train.
std::vector<std::string> candidates(const std::string& env_id, std::string& trained) {
  trained = env_id;
  std::string id = env_id;
  const bool gymnasium = id.starts_with(kGymnasiumPrefix);
  if (gymnasium) id = id.substr(kGymnasiumPrefix.size());
  std::vector<std::string> names{id};
  for (const auto& [old_id, new_id] : kRenamed) {
    if (id == old_id) {
      if (!gymnasium) trained = new_id;  // rlrun's own env is the new one
      names.push_back(new_id);
    } else if (id == new_id) {
      names.push_back(old_id);
    }
  }
  names.push_back("default");
  return names;
}

}  // namespace

std::string current_env_id(const std::string& zoo_env_id) {
  for (const auto& [old_id, new_id] : kRenamed)
    if (zoo_env_id == old_id) return new_id;
  return zoo_env_id;
}

std::string algorithm_of_file(const std::string& path) {
  return rlrun_algorithm(std::filesystem::path(path).stem().string());
}

namespace {

// The rlrun algorithm: --algo's, else the file name's; an algorithm rlrun lacks is named.
std::string choose_algorithm(const std::string& path, const std::string& algorithm) {
  if (!algorithm.empty()) {
    if (const std::string found = rlrun_algorithm(algorithm); !found.empty()) return found;
    const std::string missing = missing_algorithm(algorithm);
    throw ConfigError("--algo " + quoted_text(algorithm) + ": " +
                      (missing.empty() ? "" : missing + "; ") + kImported);
  }
  if (const std::string found = algorithm_of_file(path); !found.empty()) return found;
  const std::string missing = missing_algorithm(std::filesystem::path(path).stem().string());
  if (!missing.empty()) throw ConfigError(path + ": " + missing + "; " + kImported);
  throw ConfigError(path +
                    ": the file name does not name an algorithm (ppo.yml, a2c.yml, "
                    "dqn.yml, sac.yml, td3.yml, ddpg.yml, tqc.yml): pass --algo");
}

}  // namespace

ZooEntry read_zoo_entry(const std::string& path, const std::string& env_id,
                        const std::string& algorithm, const std::string& entry_name) {
  try {
    if (!valid_utf8(env_id))
      throw ConfigError("env id '" + quoted_text(env_id) + "': not UTF-8 text");
    ZooEntry entry;
    entry.file = path;
    entry.algorithm = choose_algorithm(path, algorithm);
    const ConfigNode root = ConfigNode::load_file(path, ConfigTrust::kUntrusted);
    if (!root.is_map()) root.fail("a zoo hyperparameter file is a map from env ids to entries");
    std::vector<std::string> names = candidates(env_id, entry.env_id);
    if (!entry_name.empty()) {
      if (!root.has(entry_name))
        root.fail("no entry " + quoted_text(entry_name) + did_you_mean(entry_name, root.keys()));
      names = {entry_name};
    }
    for (const std::string& name : names) {
      if (!root.has(name)) continue;
      entry.entry_name = name;
      entry.node = root.child(name);
      if (!entry.node.is_map()) entry.node.fail("a zoo entry is a map of hyperparameters");
      check_entry_size(entry);
      return entry;
    }
    root.fail("no entry for " + quoted_text(env_id) + " and no `default` entry" +
              did_you_mean(env_id, root.keys()) +
              " (rl-zoo stops here too: \"Hyperparameters "
              "not found\")");
  } catch (const ConfigError& e) {
    throw ConfigError(bounded_message(e.what()));
  }
}

}  // namespace rlrun::zoo
