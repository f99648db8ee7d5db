#include "rlrun/runtime/io/agent_team_file.hpp"

#include <sys/stat.h>

#include <nlohmann/json.hpp>

#include "rlrun/core/dir_handle.hpp"
#include "rlrun/core/errors.hpp"

namespace rlrun {

namespace {

constexpr const char* kFormat = "rlrun agents";
constexpr int kVersion = 1;
// A team of the most env copies' worth of agents at a few hundred bytes each fits with room;
// the bound only keeps a planted file from costing memory.
constexpr uint64_t kMaxTeamFileBytes = uint64_t{4} << 20;
constexpr size_t kMaxAgents = 65536;

// "a/b/c" -> {a, b, c}, or nullopt when a part is empty, "." or "..", or the path absolute.
std::optional<std::vector<std::string>> plain_parts(const std::string& path) {
  std::vector<std::string> parts;
  std::string part;
  for (size_t i = 0; i <= path.size(); ++i) {
    if (i < path.size() && path[i] != '/') {
      part += path[i];
      continue;
    }
    if (part.empty() || part == "." || part == ".." || part.find('\0') != std::string::npos)
      return std::nullopt;
    parts.push_back(std::move(part));
    part.clear();
  }
  return parts;
}

// The string at `key` of `object`, or a failure naming the file.
std::string text_at(const nlohmann::json& object, const char* key, const std::string& shown) {
  const auto it = object.find(key);
  if (it == object.end() || !it->is_string())
    throw RuntimeFailure(shown + ": \"" + key + "\" is missing or not a string");
  return it->get<std::string>();
}

}  // namespace

std::string agent_team_json(const AgentTeam& team) {
  nlohmann::ordered_json json;
  json["format"] = kFormat;
  json["version"] = kVersion;
  json["env"] = team.env_id;
  json["algorithm"] = team.algorithm;
  json["agents"] = nlohmann::ordered_json::array();
  for (const AgentTeamMember& member : team.agents)
    json["agents"].push_back({{"name", member.name}, {"run_dir", member.run_dir}});
  return json.dump(2) + "\n";
}

std::optional<std::string> agent_team_directory(const std::string& path) {
  // stat, not lstat: a team directory named through a link is recognised here, then refused
  // with the reason by read_agent_team (the run directory itself is never entered by a link).
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0) return std::nullopt;
  if (S_ISDIR(st.st_mode)) {
    struct stat file {};
    const std::string team_file = path + "/" + kAgentTeamFile;
    if (::lstat(team_file.c_str(), &file) != 0) return std::nullopt;
    return path;
  }
  const size_t slash = path.rfind('/');
  const std::string name = slash == std::string::npos ? path : path.substr(slash + 1);
  if (name != kAgentTeamFile) return std::nullopt;
  return slash == std::string::npos ? std::string(".") : path.substr(0, slash);
}

AgentTeamModels read_agent_team(const std::string& team_dir) {
  const DirHandle dir = DirHandle::open(team_dir);
  const std::string shown = dir.child(kAgentTeamFile);
  const std::optional<std::string> text = dir.read(kAgentTeamFile, kMaxTeamFileBytes);
  if (!text) throw RuntimeFailure(shown + " does not exist");
  nlohmann::json json;
  try {
    json = nlohmann::json::parse(*text);
  } catch (const nlohmann::json::exception& e) {
    throw RuntimeFailure(shown + " is not JSON: " + e.what());
  }
  if (!json.is_object() || json.value("format", "") != kFormat)
    throw RuntimeFailure(shown + " is not an rlrun team file (\"format\": \"" + kFormat + "\")");
  if (!json.contains("version") || json["version"] != kVersion)
    throw RuntimeFailure(shown + ": version " + json.value("version", nlohmann::json()).dump() +
                         " is not one this rlrun reads (" + std::to_string(kVersion) + ")");
  AgentTeamModels models;
  models.team.env_id = text_at(json, "env", shown);
  models.team.algorithm = text_at(json, "algorithm", shown);
  const auto agents = json.find("agents");
  if (agents == json.end() || !agents->is_array() || agents->size() < 2 ||
      agents->size() > kMaxAgents)
    throw RuntimeFailure(shown + ": \"agents\" must list 2 to " + std::to_string(kMaxAgents) +
                         " agents");
  for (const nlohmann::json& agent : *agents) {
    if (!agent.is_object()) throw RuntimeFailure(shown + ": an agent is not an object");
    AgentTeamMember member{text_at(agent, "name", shown), text_at(agent, "run_dir", shown)};
    const std::optional<std::vector<std::string>> parts = plain_parts(member.run_dir);
    if (!parts)
      throw RuntimeFailure(shown + ": agent " + member.name + "'s run_dir \"" + member.run_dir +
                           "\" is not a relative path of plain names inside the run directory");
    // Every directory on the way is opened without following a link (DirHandle::subdir).
    const DirHandle* at = &dir;
    std::optional<DirHandle> below;
    for (const std::string& part : *parts) {
      below = at->subdir(part);
      if (!below)
        throw RuntimeFailure(shown + ": agent " + member.name + "'s run directory " + team_dir +
                             "/" + member.run_dir + " does not exist");
      at = &*below;
    }
    if (at->kind("model.zip") != EntryKind::kRegular)
      throw RuntimeFailure(shown + ": agent " + member.name + " has no model file " +
                           at->child("model.zip") + " (a regular file, not a link)");
    models.model_paths.push_back(team_dir + "/" + member.run_dir + "/model.zip");
    models.team.agents.push_back(std::move(member));
  }
  return models;
}

}  // namespace rlrun
