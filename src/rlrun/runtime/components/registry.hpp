#pragma once
// The component registry: ids (as written in YAML) -> parsers and factories. A value: main()
// builds one (runtime/components/builtins.hpp: the built-in envs of every env folder, the wrappers and the
// algorithms), adds the plugins the command line names, and passes it down; `rlrun list`
// prints it.
// Lookups of unknown ids fail with the YAML position and the closest registered id.
#include <deque>
#include <functional>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "rlrun/core/any_config.hpp"
#include "rlrun/core/config_checks.hpp"
#include "rlrun/core/config_fields.hpp"
#include "rlrun/core/config_node.hpp"
#include "rlrun/env.hpp"
#include "rlrun/env/env_entry.hpp"

namespace rlrun {

class Algorithm;
struct AlgorithmSetup;

// Each entry parses its section into a typed Config once (strictly: unknown keys, types and
// value constraints, all problems at once as one ConfigError) and builds from that value.
struct WrapperEntry {
  std::string id;
  std::string description;
  std::function<AnyConfig(const ConfigNode& params)> parse;
  std::function<EnvPtr(EnvPtr inner, const AnyConfig& params)> make;
  std::function<std::vector<FieldDoc>()> params;
};

struct AlgorithmEntry {
  std::string id;
  std::string description;
  std::vector<SpaceKind> action_spaces;  // SB3's support table (docs/guide/algos.rst)
  std::function<AnyConfig(const ConfigNode& params)> parse;
  // Checks that need the env's spaces or several values at once (before anything trains).
  std::function<ConfigProblems(const AnyConfig& params, const AlgorithmSetup&)> check;
  std::function<std::unique_ptr<Algorithm>(const AnyConfig& params, const AlgorithmSetup&)> make;
  std::function<std::vector<FieldDoc>()> params;
};

class Registry {
 public:
  void add(EnvEntry entry) { envs_.push_back(std::move(entry)); }
  void add(WrapperEntry entry) { wrappers_.push_back(std::move(entry)); }
  void add(AlgorithmEntry entry) { algorithms_.push_back(std::move(entry)); }
  // Puts `entry` in place of the env of its id (a family member too): a run that builds that
  // env in its own way (per-agent training's seats, runtime/run/per_agent_training.hpp) works
  // on a copy of the registry with it.
  void replace_env(EnvEntry entry) {
    std::erase_if(envs_, [&](const EnvEntry& e) { return e.id == entry.id; });
    envs_.insert(envs_.begin(), std::move(entry));
  }

  // `id_node` is the YAML node holding the id, for the error position.
  // Ids of a family (EnvEntry::expand, e.g. python:module:Class) are expanded on first use.
  const EnvEntry& env(const std::string& id, const ConfigNode& id_node) const {
    std::string why;
    if (const EnvEntry* e = find_env(id, &why)) return *e;
    if (!why.empty()) id_node.fail(why);
    return find(envs_, id, id_node, "environment");
  }
  const WrapperEntry& wrapper(const std::string& id, const ConfigNode& id_node) const {
    return find(wrappers_, id, id_node, "wrapper");
  }
  const AlgorithmEntry& algorithm(const std::string& id, const ConfigNode& id_node) const {
    return find(algorithms_, id, id_node, "algorithm");
  }
  // nullptr for an unknown id; `why` (if given) says what is wrong with a malformed family id.
  const EnvEntry* find_env(const std::string& id, std::string* why = nullptr) const {
    if (const EnvEntry* e = find_or_null(envs_, id); e && !e->expand) return e;
    const std::lock_guard<std::mutex> lock(*expanded_mutex_);
    if (const EnvEntry* e = find_or_null(expanded_, id)) return e;
    for (const EnvEntry& family : envs_) {
      if (!family.expand || id.size() < family.id.size() ||
          id.compare(0, family.id.size(), family.id) != 0)
        continue;
      try {
        expanded_.push_back(family.expand(id));
      } catch (const std::invalid_argument& e) {
        if (why) *why = e.what();
        return nullptr;
      }
      expanded_.back().id = id;
      return &expanded_.back();
    }
    return nullptr;
  }
  const WrapperEntry* find_wrapper(const std::string& id) const {
    return find_or_null(wrappers_, id);
  }
  const AlgorithmEntry* find_algorithm(const std::string& id) const {
    return find_or_null(algorithms_, id);
  }

  const std::vector<EnvEntry>& envs() const { return envs_; }
  const std::vector<WrapperEntry>& wrappers() const { return wrappers_; }
  const std::vector<AlgorithmEntry>& algorithms() const { return algorithms_; }

 private:
  template <class Entries>
  static const typename Entries::value_type* find_or_null(const Entries& entries,
                                                          const std::string& id) {
    for (const auto& e : entries)
      if (e.id == id) return &e;
    return nullptr;
  }
  template <class Entry>
  static const Entry& find(const std::vector<Entry>& entries, const std::string& id,
                           const ConfigNode& id_node, const char* kind) {
    if (const Entry* e = find_or_null(entries, id)) return *e;
    std::vector<std::string> ids;
    for (const auto& e : entries) ids.push_back(e.id);
    id_node.fail(std::string("unknown ") + kind + " '" + id + "'" + did_you_mean(id, ids) +
                 "; run `rlrun list` to see all");
  }

  std::vector<EnvEntry> envs_;
  // Family members built by find_env (a deque: entries keep their address, so a pointer
  // handed out stays valid). Any thread may look up (two rlrun::Policy::load at once): the
  // mutex guards the deque; a copy of the registry shares it, which only serialises more.
  mutable std::deque<EnvEntry> expanded_;
  std::shared_ptr<std::mutex> expanded_mutex_ = std::make_shared<std::mutex>();
  std::vector<WrapperEntry> wrappers_;
  std::vector<AlgorithmEntry> algorithms_;
};

// Registration helpers for components whose constructor takes their own `Config`.
template <class W>
WrapperEntry make_wrapper_entry(std::string id, std::string description) {
  WrapperEntry entry;
  entry.id = std::move(id);
  entry.description = std::move(description);
  entry.parse = [](const ConfigNode& params) {
    return AnyConfig::of(read_config<typename W::Config>(params, {"id"}));
  };
  entry.make = [](EnvPtr inner, const AnyConfig& params) -> EnvPtr {
    return std::make_unique<W>(std::move(inner), params.get<typename W::Config>());
  };
  entry.params = [] { return document_config<typename W::Config>(); };
  return entry;
}

template <class A>
AlgorithmEntry make_algorithm_entry(std::string id, std::string description) {
  AlgorithmEntry entry;
  entry.id = std::move(id);
  entry.description = std::move(description);
  entry.action_spaces.assign(std::begin(A::kActionSpaces), std::end(A::kActionSpaces));
  entry.parse = [](const ConfigNode& params) {
    return AnyConfig::of(read_config<typename A::Config>(params, {"id"}));
  };
  entry.check = [](const AnyConfig& params, const AlgorithmSetup& setup) {
    return A::check(params.get<typename A::Config>(), setup);
  };
  entry.make = [](const AnyConfig& params,
                  const AlgorithmSetup& setup) -> std::unique_ptr<Algorithm> {
    return std::make_unique<A>(params.get<typename A::Config>(), setup);
  };
  entry.params = [] { return document_config<typename A::Config>(); };
  return entry;
}

}  // namespace rlrun
