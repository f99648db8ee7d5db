#pragma once
// The `env:` section of an experiment file, as plain data: the section's own settings, the env
// id with its parsed kwargs, and the wrapper stack (runtime/experiment/env_factory.hpp builds
// it).
#include <optional>
#include <string>
#include <vector>

#include "rlrun/core/any_config.hpp"
#include "rlrun/core/config_checks.hpp"
#include "rlrun/core/trusted_values.hpp"
#include "rlrun/space.hpp"
#include "rlrun/wrappers/vec_normalize.hpp"

namespace rlrun {

// An upper bound on n_envs: each env holds a monitor file open (and a simulator may hold
// sockets); beyond a few thousand, the gain is nil on any CPU rlrun runs on.
inline constexpr int kMaxEnvs = 4096;

struct EnvSectionConfig {
  int n_envs = 1;                        // parallel env copies (SB3 n_envs)
  std::optional<int> max_episode_steps;  // override the registered time limit
  bool auto_wrap = false;                // add the action-space wrapper the algorithm needs
  ProgramPath python{"python3"};         // interpreter of python:/gymnasium:/pettingzoo: envs
  double startup_timeout = 60.0;         // seconds their worker may take to build the env
  std::string opponent = "self";         // turn-based pettingzoo: games (pettingzoo_agents.py)
  std::string learner_side = "alternate";
  std::string agent_indicator = "none";  // pettingzoo: envs (SuperSuit's agent_indicator_v0)
  // Multi-agent envs: one policy shared by the agents, or one learner per agent
  // (runtime/run/per_agent_training.hpp).
  std::string agent_policies = "shared";
  // SB3's Monitor info_keywords; null = the env's declared metrics (env/env_entry.hpp).
  std::optional<std::vector<std::string>> info_keywords;
  NormalizeSetting normalize;  // SB3 VecNormalize (wrappers/vec_normalize.hpp)
  template <class V>
  void visit(V& v) {
    v("n_envs", n_envs, "number of env copies stepped together", in_range(1, kMaxEnvs));
    v("max_episode_steps", max_episode_steps,
      "time limit override (null = registered limit; to remove a limit, use a large number)",
      at_least(1));
    v("auto_wrap", auto_wrap,
      "wrap Discrete envs with DiscreteAsBox / Box envs with BoxAsDiscrete when the algorithm "
      "needs it");
    v("python", python,
      "Python interpreter for python:/gymnasium:/pettingzoo: envs (a name on PATH or a path, e.g. "
      "a "
      "virtualenv's bin/python); the default python3 gives way to $RLRUN_PYTHON when set");
    v("startup_timeout", startup_timeout,
      "seconds a python:/gymnasium:/pettingzoo: env's worker may take to import its module and "
      "build the "
      "env (its __init__) before rlrun stops it with an error",
      in_range(0, 1e6).open_low());
    v("opponent", opponent,
      "turn-based pettingzoo: games (tic-tac-toe, connect four): who plays the seats the learner "
      "does not. self: the one policy plays whichever seat is to move (PettingZoo's SB3 "
      "tutorial); random: random legal moves, the learner plays one seat",
      OneOf{{"self", "random"}});
    v("learner_side", learner_side,
      "with opponent: random, the learner's seat: alternate (first, second, ... by episode), "
      "first or second",
      OneOf{{"alternate", "first", "second"}});
    v("agent_indicator", agent_indicator,
      "pettingzoo: envs: add which agent observes to its observation, as SuperSuit's "
      "agent_indicator_v0 (so the shared policy can act per agent): none, agent (one indicator "
      "per agent) or type (one per <type>_<n> agent type)",
      OneOf{{"none", "agent", "type"}});
    v("agent_policies", agent_policies,
      "multi-agent envs: shared (one policy learns from every agent, SuperSuit's parameter "
      "sharing) or per_agent (independent learners: each agent its own networks, optimiser and "
      "run directory under agents/)",
      OneOf{{"shared", "per_agent"}});
    v("info_keywords", info_keywords,
      "info keys read at each episode's end: monitor.csv columns, rollout/<key> and eval/<key> "
      "means (SB3's Monitor info_keywords); null = the env's metrics and is_success, [] = none");
    v("normalize", normalize,
      "SB3 VecNormalize on the training envs (rl-zoo's normalize): true, or {norm_obs, "
      "norm_reward, clip_obs, clip_reward, gamma (null = the algorithm's), epsilon}");
  }
};

struct WrapperSpec {
  std::string id;
  AnyConfig params;
};

struct EnvSpec {
  std::string id;
  std::string where;  // "file:line:col" of env.id, for messages after parsing
  EnvSectionConfig section;
  AnyConfig kwargs;  // the env's Config (empty: its defaults)
  std::vector<WrapperSpec> wrappers;
  // Set from the algorithm: the action spaces it supports and its id, for the check (and
  // auto_wrap) at the end of the env stack. Empty: no check.
  std::vector<SpaceKind> accepted_action_spaces;
  std::string algorithm_id;
  // The algorithm's gamma, for env.normalize's `gamma: null` (unset: VecNormalize's 0.99).
  std::optional<double> algorithm_gamma;
  double normalize_gamma() const {
    return section.normalize.gamma.value_or(algorithm_gamma.value_or(0.99));
  }
};

}  // namespace rlrun
