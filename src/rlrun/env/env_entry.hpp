#pragma once
// What an env folder registers for each of its envs (Gymnasium's gymnasium.register): its id,
// a description, the time limit gymnasium.make would add, how its `kwargs` are parsed into its
// typed Config and how it is built from that, and the baseline policies that come with it
// (`eval --policy` / `--baseline`, `record --policy`). Each folder under src/rlrun/envs/ has
// one register.cpp listing its entries; CMake collects the folders (runtime/components/builtins.cpp), so
// nothing above envs/ names a concrete env.
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "rlrun/core/any_config.hpp"
#include "rlrun/core/config_fields.hpp"
#include "rlrun/core/config_node.hpp"
#include "rlrun/env.hpp"
#include "rlrun/env/env_spaces.hpp"
#include "rlrun/env/policy.hpp"

namespace rlrun {

// A baseline that comes with an env. `make` throws UsageError when the env it is given does
// not fit (another env id, settings out of range).
struct PolicyEntry {
  std::string name;         // as typed after --policy / --baseline, e.g. "fixed-time"
  std::string description;  // one line for `rlrun list ID`
  std::function<PolicyFn(Env& env, const PolicyOptions& options)> make;
};

// What the experiment (not the env's kwargs) decides about how an env is built: the
// `env.python` interpreter of Python envs and the seconds its worker may take to start
// (`env.startup_timeout`).
struct EnvContext {
  std::string python = "python3";
  double startup_timeout = 60.0;
  // Turn-based PettingZoo games (pettingzoo: envs): who plays the seats the learner does not
  // ("self" or "random") and the learner's seat ("alternate", "first", "second").
  std::string opponent = "self";
  std::string learner_side = "alternate";
  // pettingzoo: envs: the observing agent's indicator in its observation (none, agent, type).
  std::string agent_indicator = "none";
};

struct EnvEntry {
  std::string id;
  std::string description;
  int max_episode_steps = 0;  // TimeLimit added by make_env, like gymnasium.make; 0 = none
  std::function<AnyConfig(const ConfigNode& kwargs)> parse;  // strict; all problems at once
  std::function<EnvPtr(const AnyConfig& kwargs)> make;
  // The spaces of the env `kwargs` configure, learned without starting a simulator or a worker
  // (experiment parsing, `rlrun list`). Envs that live in this process are built and asked:
  // their constructors read files at most (SUMO starts at the first reset, and so does a
  // Bullet world). Unset for envs whose spaces only a running worker knows (python:,
  // gymnasium:): parsing then leaves the checks that need them to the first env built
  // (make_algorithm), and a model file records them (runtime/io/model_file.hpp).
  std::function<EnvSpaces(const AnyConfig& kwargs)> spaces;
  std::function<std::vector<FieldDoc>()> params;
  std::vector<PolicyEntry> policies;
  // The info keys that measure how well an episode went, read at its last step (the traffic
  // task's avg_waiting_time, the grasp task's lift): by default Monitor writes them as
  // monitor.csv columns (SB3's info_keywords) and training logs their means over the last 100
  // episodes as rollout/<key> (`env.info_keywords` chooses others). is_success is always one
  // when the env declares it.
  std::vector<std::string> metrics;
  std::string plugin;  // the library that registered it ("" for built-in envs)

  // Set instead of `make` by envs that need the EnvContext (Python envs).
  std::function<EnvPtr(const AnyConfig& kwargs, const EnvContext& context)> make_in_context;
  // A family of ids: `id` is a prefix ("python:") and expand(full id) gives the entry of one
  // member ("python:my_pkg.my_mod:MyEnv"), or throws std::invalid_argument saying why the id
  // is malformed. Registry::find_env expands on first use.
  std::function<EnvEntry(const std::string& id)> expand;
  // The id names code that building the env runs (a Python class): an id from a file rlrun
  // does not trust is refused unless `--set env.id=...` vouches for it (docs/security.md).
  bool runs_named_code = false;
  // Copies of this env share nothing a step changes (each its own simulation and RNG, no
  // process-wide state): a VecEnv may step them on several threads at once (env/vec_env.hpp).
  // Built-in envs that simulate in this process say so. Envs in other processes overlap
  // already (env/split_step.hpp); plugin envs are not assumed to.
  bool independent_copies = false;

  EnvPtr build(const AnyConfig& kwargs, const EnvContext& context) const {
    return make_in_context ? make_in_context(kwargs, context) : make(kwargs);
  }
};

using EnvEntries = std::vector<EnvEntry>;

// Sets independent_copies on out[first], out[first + 1], ...: the entries a folder's
// register function added.
inline void mark_independent_copies(EnvEntries& out, size_t first) {
  for (size_t i = first; i < out.size(); ++i) out[i].independent_copies = true;
}

// The entry of an env class whose constructor takes its own `Config`.
template <class E>
EnvEntry make_env_entry(std::string id, std::string description, int max_episode_steps) {
  EnvEntry entry;
  entry.id = std::move(id);
  entry.description = std::move(description);
  entry.max_episode_steps = max_episode_steps;
  entry.parse = [](const ConfigNode& kwargs) {
    return AnyConfig::of(read_config<typename E::Config>(kwargs));
  };
  entry.make = [](const AnyConfig& kwargs) -> EnvPtr {
    return std::make_unique<E>(kwargs.get<typename E::Config>());
  };
  entry.spaces = [](const AnyConfig& kwargs) {
    return spaces_of(E(kwargs.get<typename E::Config>()));
  };
  entry.params = [] { return document_config<typename E::Config>(); };
  return entry;
}

}  // namespace rlrun
