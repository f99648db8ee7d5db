// rlrun list [ID]: the registered environments, wrappers and algorithms; with an id, that
// component's parameters, defaults and docs.
#include <algorithm>
#include <cstdio>
#include <memory>

#include "commands.hpp"
#include "plugin_option.hpp"
#include "rlrun/core/errors.hpp"
#include "rlrun/env/space_text.hpp"
#include "rlrun/runtime/builtins.hpp"

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

void print_params(const std::string& id, const std::vector<FieldDoc>& rows) {
  std::printf("%s parameters:\n", id.c_str());
  if (rows.empty()) std::printf("  (none)\n");
  size_t key_width = 0, value_width = 0;
  for (const auto& r : rows) {
    key_width = std::max(key_width, r.key.size());
    value_width = std::max(value_width, r.default_value.size());
  }
  for (const auto& r : rows)
    std::printf("  %-*s  %-*s  %s\n", static_cast<int>(key_width), r.key.c_str(),
                static_cast<int>(value_width), r.default_value.c_str(), r.doc.c_str());
}

template <class Entries>
const auto* find_entry(const Entries& entries, const std::string& id) {
  for (const auto& e : entries)
    if (e.id == id) return &e;
  return static_cast<const typename Entries::value_type*>(nullptr);
}

// An env's spaces, from one built with its default parameters.
void print_spaces(const EnvEntry& entry) {
  EnvPtr env;
  try {
    env = entry.make(entry.parse(ConfigNode()));
  } catch (const std::exception& e) {
    std::printf("  (spaces unknown: the env cannot be built with its defaults: %s)\n", e.what());
    return;
  }
  std::printf("%s", labeled_space("observation_space", env->observation_space(), 17).c_str());
  std::printf("%s", labeled_space("action_space", env->action_space(), 17).c_str());
}

void print_action_spaces(const AlgorithmEntry& entry) {
  std::string names;
  for (SpaceKind k : entry.action_spaces) names += (names.empty() ? "" : ", ") + std::string(space_kind_name(k));
  std::printf("  action spaces      %s\n", names.c_str());
}

}  // namespace

Action add_list(CLI::App& app) {
  auto id = std::make_shared<std::string>();
  CLI::App* sub = app.add_subcommand("list", "list registered environments, wrappers and algorithms");
  sub->add_option("id", *id, "show the parameters of one component, e.g. `rlrun list PPO`");
  auto plugins = std::make_shared<std::vector<std::string>>();
  add_plugin_option(sub, *plugins);
  return [id, plugins]() {
    load_plugin_options(*plugins);
    const Registry& r = builtin_registry();
    if (id->empty()) {
      print_table("environments", r.envs());
      print_table("wrappers", r.wrappers());
      print_table("algorithms", r.algorithms());
      std::printf("\n`rlrun list ID` shows a component's parameters and defaults.\n");
      return 0;
    }
    if (const EnvEntry* env = find_entry(r.envs(), *id)) {
      print_params(env->id, env->params());
      print_spaces(*env);
      return 0;
    }
    if (const WrapperEntry* wrapper = find_entry(r.wrappers(), *id)) {
      print_params(wrapper->id, wrapper->params());
      return 0;
    }
    if (const AlgorithmEntry* algo = find_entry(r.algorithms(), *id)) {
      print_params(algo->id, algo->params());
      print_action_spaces(*algo);
      return 0;
    }
    std::vector<std::string> ids;
    for (const auto& e : r.envs()) ids.push_back(e.id);
    for (const auto& e : r.wrappers()) ids.push_back(e.id);
    for (const auto& e : r.algorithms()) ids.push_back(e.id);
    throw UsageError("no component '" + *id + "'" + did_you_mean(*id, ids));
  };
}

}  // namespace rlrun::cli
