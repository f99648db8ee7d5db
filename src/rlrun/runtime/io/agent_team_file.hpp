#pragma once
// agents.json: the team a per-agent run trained (runtime/run/per_agent_training.hpp), in its
// run directory: the env, the algorithm, and each agent's name with its own run directory
// (relative, under agents/), whose model.zip is the agent's policy.
//   {"format": "rlrun agents", "version": 1, "env": "TrafficNetwork-v0", "algorithm": "PPO",
//    "agents": [{"name": "A0", "run_dir": "agents/A0/seed1"}, ...]}
// A run directory may come from anyone (docs/security.md): the file is read without following
// links and with a bound, and each run_dir must be plain names inside the team's directory
// (no "..", no absolute path, no link on the way) holding a regular model.zip.
#include <optional>
#include <string>
#include <vector>

namespace rlrun {

inline constexpr const char* kAgentTeamFile = "agents.json";

struct AgentTeamMember {
  std::string name;     // the env's name of the agent (env/agent_names.hpp)
  std::string run_dir;  // relative to the team's run directory
};

struct AgentTeam {
  std::string env_id;
  std::string algorithm;
  std::vector<AgentTeamMember> agents;
};

std::string agent_team_json(const AgentTeam& team);

// The team's run directory when `path` is one (a directory holding agents.json) or is an
// agents.json; nullopt otherwise (a model file, or nothing).
std::optional<std::string> agent_team_directory(const std::string& path);

// The team of run directory `team_dir` and each agent's model file (a path under team_dir).
// Throws RuntimeFailure naming the file for anything wrong in it.
struct AgentTeamModels {
  AgentTeam team;
  std::vector<std::string> model_paths;
};
AgentTeamModels read_agent_team(const std::string& team_dir);

}  // namespace rlrun
