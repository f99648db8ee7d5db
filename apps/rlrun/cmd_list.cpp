// rlrun list [ID]: the registered environments, wrappers and algorithms; with an id, that
// component's parameters, defaults and docs.
#include <algorithm>
#include <cstdio>
#include <memory>
#include <type_traits>

#include "commands.hpp"
#include "plugin_option.hpp"
#include "rlrun/core/errors.hpp"
#include "rlrun/env/space_text.hpp"
#include "rlrun/runtime/components/builtins.hpp"
#include "rlrun/runtime/components/optional_components.hpp"

namespace rlrun::cli {

namespace {

template <class Entries>
void print_table(const char* title, const Entries& entries) {
  std::printf("%s:\n", title);
  if (entries.empty()) std::printf("  (none yet)\n");
  size_t width = 0;
  for (const auto& e : entries) width = std::max(width, e.id.size());
  for (const auto& e : entries)
    std::printf("  %-*s  %s\n", static_cast<int>(width), e.id.c_str(), e.description.c_str());
}

// An env's spaces (as built with default parameters), time limit, metrics and policies.
void print_env_details(const EnvEntry& entry) {
  if (const OptionalComponent* component = unbuilt_component_of(entry.id)) {
    std::printf("%s\n", unbuilt_env_message(entry.id, *component).c_str());
    return;
  }
  std::printf("%s: %s\n", entry.id.c_str(), entry.description.c_str());
  if (entry.expand) {
    std::printf(
        "  a family of ids: the spaces are the env's own (`rlrun check-env %s...` builds one "
        "and shows them);\n  env.kwargs go to its constructor as keyword arguments, env.python "
        "picks the interpreter (docs/python.md)\n",
        entry.id.c_str());
    return;
  }
  try {
    // As the entry declares them: no simulator or worker starts (env/env_entry.hpp).
    const EnvSpaces spaces = entry.spaces(entry.parse(ConfigNode()));
    std::printf("%s", labeled_space("observation_space", spaces.observation, 17).c_str());
    std::printf("%s", labeled_space("action_space", spaces.action, 17).c_str());
    if (spaces.num_agents > 1) std::printf("  agents             %d\n", spaces.num_agents);
  } catch (const std::exception& e) {
    std::printf("  (spaces unknown: the env cannot be built with its defaults: %s)\n", e.what());
  }
  std::printf("  time limit         %s\n", entry.max_episode_steps > 0
                                               ? std::to_string(entry.max_episode_steps).c_str()
                                               : "none (the env ends its own episodes)");
  if (!entry.metrics.empty()) {
    std::string metrics;
    for (const std::string& m : entry.metrics) metrics += (metrics.empty() ? "" : ", ") + m;
    std::printf("  metrics            %s (monitor.csv columns, rollout/<key>, eval/<key>)\n",
                metrics.c_str());
  }
  std::printf("  policies           random (uniform actions)\n");
  for (const PolicyEntry& policy : entry.policies)
    std::printf("                     %s (%s)\n", policy.name.c_str(), policy.description.c_str());
}

void print_action_spaces(const AlgorithmEntry& entry) {
  std::string names;
  for (SpaceKind k : entry.action_spaces)
    names += (names.empty() ? "" : ", ") + std::string(space_kind_name(k));
  std::printf("  action spaces      %s\n", names.c_str());
}

void print_params(const std::string& id, const std::vector<FieldDoc>& rows) {
  std::printf("%s parameters:\n", id.c_str());
  if (rows.empty()) std::printf("  (none)\n");
  size_t key_width = 0, value_width = 0;
  for (const auto& r : rows) {
    key_width = std::max(key_width, r.key.size());
    value_width = std::max(value_width, r.default_value.size());
  }
  for (const auto& r : rows)
    std::printf("  %-*s  %-*s  %s%s\n", static_cast<int>(key_width), r.key.c_str(),
                static_cast<int>(value_width), r.default_value.c_str(), r.doc.c_str(),
                r.constraint.empty() ? "" : (" [" + r.constraint + "]").c_str());
}

template <class Entries>
bool print_params_if_found(const Entries& entries, const std::string& id) {
  for (const auto& e : entries) {
    if (e.id != id) continue;
    using Entry = std::decay_t<decltype(e)>;
    if constexpr (std::is_same_v<Entry, EnvEntry>) {
      print_env_details(e);
      if (e.expand) return true;
    }
    print_params(e.id, e.params());
    if constexpr (std::is_same_v<Entry, AlgorithmEntry>) print_action_spaces(e);
    return true;
  }
  return false;
}

}  // namespace

Action add_list(CLI::App& app, Registry& registry) {
  auto id = std::make_shared<std::string>();
  CLI::App* sub =
      app.add_subcommand("list", "list registered environments, wrappers and algorithms");
  sub->add_option("id", *id, "show the parameters of one component, e.g. `rlrun list PPO`");
  auto plugins = std::make_shared<std::vector<std::string>>();
  add_plugin_option(sub, *plugins);
  return [id, plugins, &registry]() {
    load_plugin_options(*plugins, registry);
    const Registry& r = registry;
    if (id->empty()) {
      print_table("environments", r.envs());
      print_table("wrappers", r.wrappers());
      print_table("algorithms", r.algorithms());
      std::printf("\n`rlrun list ID` shows a component's parameters and defaults.\n");
      return 0;
    }
    if (print_params_if_found(r.envs(), *id) || print_params_if_found(r.wrappers(), *id) ||
        print_params_if_found(r.algorithms(), *id))
      return 0;
    std::vector<std::string> ids;
    for (const auto& e : r.envs()) ids.push_back(e.id);
    for (const auto& e : r.wrappers()) ids.push_back(e.id);
    for (const auto& e : r.algorithms()) ids.push_back(e.id);
    throw UsageError("no component '" + *id + "'" + did_you_mean(*id, ids));
  };
}

}  // namespace rlrun::cli
