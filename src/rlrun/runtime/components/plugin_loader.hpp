#pragma once
// Loads users' env plugins: shared libraries built against include/rlrun/ (the plugin API)
// that export `rlrun_plugin_register` (RLRUN_PLUGIN in rlrun/plugin.hpp). A plugin is loaded
// once per process (later requests for the same file do nothing), its API version is checked
// before any of its C++ objects is used, and its envs are added to the registry with their
// Config parameters, so YAML, `--set`, `rlrun list` and model files treat them like
// built-in envs; each entry records its library (EnvEntry::plugin). Libraries stay loaded
// until the process ends (their code backs the envs).
#include <cstdint>
#include <string>
#include <vector>

#include "rlrun/core/config_node.hpp"
#include "rlrun/registrar.hpp"
#include "rlrun/runtime/components/registry.hpp"

namespace rlrun {

// The plugin's exported function (see rlrun/plugin.hpp for the contract).
using PluginEntry = uint32_t (*)(uint32_t host_api_version, api::Registrar* registrar);

// Finds the library a user named: an existing file relative to `base_dir` (the current
// directory when empty) becomes an absolute path; a bare file name that does not exist there
// is left to the dynamic loader's search path (LD_LIBRARY_PATH). Throws UsageError for a
// path with a directory part that does not exist.
std::string resolve_plugin_path(const std::string& path, const std::string& base_dir = "");

// dlopen()s `path` (resolved as above), checks its API version and adds its envs to
// `registry`. Returns the resolved path. Throws UsageError saying what to do when the file
// cannot be loaded, is not an rlrun plugin, was built for another API version, or registers
// an env id that already exists.
std::string load_plugin(const std::string& path, Registry& registry);

// Runs a plugin's registration function (load_plugin's second half; tests call it with an
// entry compiled into the test binary). `name` names the plugin in messages.
void register_plugin(PluginEntry entry, const std::string& name, Registry& registry);

// The YAML `plugins:` list of the user's own experiment file: paths relative to the file's
// directory. Loads each into `registry` and returns their resolved paths; a problem is a
// ConfigError at the list item. (Lists inside untrusted files are never loaded.)
std::vector<std::string> load_plugins_section(const ConfigNode& plugins, Registry& registry);

// The directory a `plugins:` list's relative paths start from (the file's), or "".
std::string plugin_base_dir(const ConfigNode& plugins);

}  // namespace rlrun
