#include "rlrun/runtime/zoo/zoo_file.hpp"

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <utility>
#include <vector>

#include "rlrun/core/errors.hpp"

namespace rlrun::zoo {

namespace {

// rl-zoo's algorithm names (rl_zoo3/utils.py ALGOS) that rlrun implements.
const std::vector<std::pair<std::string, std::string>> kAlgorithms{
    {"ppo", "PPO"}, {"a2c", "A2C"}, {"dqn", "DQN"}, {"sac", "SAC"},
    {"td3", "TD3"}, {"ddpg", "DDPG"}, {"tqc", "TQC"}};

// Env ids whose zoo entries were renamed with Gymnasium's versions: {old, new}.
const std::vector<std::pair<std::string, std::string>> kRenamed{
    {"LunarLander-v2", "LunarLander-v3"},
    {"LunarLanderContinuous-v2", "LunarLanderContinuous-v3"}};

std::string lower(std::string s) {
  for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

}  // namespace

std::string algorithm_of_file(const std::string& path) {
  const std::string stem = lower(std::filesystem::path(path).stem().string());
  for (const auto& [zoo, rlrun] : kAlgorithms)
    if (stem == zoo) return rlrun;
  return "";
}

ZooEntry read_zoo_entry(const std::string& path, const std::string& env_id,
                        const std::string& algorithm, const std::string& entry_name) {
  ZooEntry entry;
  entry.file = path;
  entry.algorithm = algorithm;
  if (entry.algorithm.empty()) {
    entry.algorithm = algorithm_of_file(path);
    if (entry.algorithm.empty())
      throw ConfigError(path + ": the file name does not name an algorithm (ppo.yml, a2c.yml, "
                        "dqn.yml, sac.yml, td3.yml, ddpg.yml, tqc.yml): pass --algo");
  } else {
    const std::string wanted = lower(entry.algorithm);
    auto it = std::find_if(kAlgorithms.begin(), kAlgorithms.end(),
                           [&](const auto& a) { return a.first == wanted; });
    if (it == kAlgorithms.end())
      throw ConfigError("--algo " + algorithm + ": rlrun imports zoo files of ppo, a2c, dqn, sac, "
                        "td3, ddpg and tqc");
    entry.algorithm = it->second;
  }
  const ConfigNode root = ConfigNode::load_file(path);
  if (!root.is_map()) root.fail("a zoo hyperparameter file is a map from env ids to entries");

  // The env trained: a renamed id's new name.
  entry.env_id = env_id;
  std::vector<std::string> candidates{env_id};
  for (const auto& [old_id, new_id] : kRenamed) {
    if (env_id == old_id) {
      entry.env_id = new_id;
      candidates.push_back(new_id);
    } else if (env_id == new_id) {
      candidates.push_back(old_id);
    }
  }
  candidates.push_back("default");
  if (!entry_name.empty()) {
    if (!root.has(entry_name))
      root.fail("no entry " + entry_name + did_you_mean(entry_name, root.keys()));
    candidates = {entry_name};
  }
  for (const std::string& name : candidates) {
    if (!root.has(name)) continue;
    entry.entry_name = name;
    entry.node = root.child(name);
    if (!entry.node.is_map()) entry.node.fail("a zoo entry is a map of hyperparameters");
    return entry;
  }
  root.fail("no entry for " + env_id + " and no `default` entry" +
            did_you_mean(env_id, root.keys()) + " (rl-zoo stops here too: \"Hyperparameters not "
            "found\")");
}

}  // namespace rlrun::zoo
