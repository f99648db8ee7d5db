#pragma once
// `--plugin LIB` (repeatable), shared by the subcommands that build envs: loads users' env
// libraries (runtime/components/plugin_loader.hpp) before any config is read, so their env ids resolve.
#include <CLI/CLI.hpp>
#include <string>
#include <vector>

#include "rlrun/runtime/components/builtins.hpp"
#include "rlrun/runtime/components/plugin_loader.hpp"

namespace rlrun::cli {

inline void add_plugin_option(CLI::App* sub, std::vector<std::string>& plugins) {
  sub->add_option("--plugin", plugins,
                  "load environments from a plugin library built against include/rlrun/ "
                  "(repeatable; see examples/custom_env)")
      ->allow_extra_args(false);
}

inline void load_plugin_options(const std::vector<std::string>& plugins, Registry& registry) {
  for (const auto& path : plugins) load_plugin(path, registry);
}

}  // namespace rlrun::cli
