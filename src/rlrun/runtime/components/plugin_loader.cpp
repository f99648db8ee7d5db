#include "rlrun/runtime/components/plugin_loader.hpp"

#include <dlfcn.h>

#include <filesystem>
#include <map>
#include <memory>
#include <stdexcept>

#include "rlrun/core/config_fields.hpp"
#include "rlrun/core/errors.hpp"
#include "rlrun/plugin.hpp"
#include "rlrun/runtime/components/builtins.hpp"
#include "rlrun/runtime/components/plugin_env.hpp"

namespace rlrun {

namespace {

namespace fs = std::filesystem;

// Lets a plugin Config's visit() talk to one of rlrun's config visitors (strict YAML reader,
// resolved-config writer, `rlrun list` documenter).
template <class Inner>
class ForwardingVisitor final : public api::FieldVisitor {
 public:
  explicit ForwardingVisitor(Inner& inner) : inner_(inner) {}
  void field(const char* k, bool& v, const char* d) override { inner_(k, v, d); }
  void field(const char* k, int& v, const char* d) override { inner_(k, v, d); }
  void field(const char* k, int64_t& v, const char* d) override { inner_(k, v, d); }
  void field(const char* k, float& v, const char* d) override { inner_(k, v, d); }
  void field(const char* k, double& v, const char* d) override { inner_(k, v, d); }
  void field(const char* k, std::string& v, const char* d) override { inner_(k, v, d); }
  void field(const char* k, std::vector<double>& v, const char* d) override { inner_(k, v, d); }
  void field(const char* k, std::vector<int64_t>& v, const char* d) override { inner_(k, v, d); }

 private:
  Inner& inner_;
};

EnvEntry make_entry(const api::EnvSpec& spec, std::shared_ptr<const api::EnvFactory> factory,
                    const std::string& plugin) {
  EnvEntry entry;
  entry.id = spec.id;
  entry.description = spec.description + " [plugin " + fs::path(plugin).filename().string() + "]";
  entry.max_episode_steps = spec.max_episode_steps;
  entry.plugin = plugin;
  const std::string id = spec.id;
  // The plugin's Config type lives in its library: parsing checks the YAML strictly and keeps
  // the resolved values, from which make() fills a fresh Config.
  entry.parse = [factory](const ConfigNode& kwargs) {
    ConfigReader reader(kwargs);
    ConfigWriter writer;
    ForwardingVisitor<ConfigReader> read(reader);
    ForwardingVisitor<ConfigWriter> write(writer);
    api::FieldVisitor* visitors[] = {&read, &write};
    factory->make(visitors, false);
    reader.finish();
    return AnyConfig::of_yaml(writer.node(), writer.node());
  };
  entry.make = [factory, id](const AnyConfig& kwargs) -> EnvPtr {
    ConfigReader reader(ConfigNode::from_yaml(kwargs.get<YAML::Node>(), id + " kwargs"));
    ForwardingVisitor<ConfigReader> visitor(reader);
    api::FieldVisitor* visitors[] = {&visitor};
    EnvPtr env;
    try {
      env = factory->make(visitors, true);
    } catch (const std::invalid_argument& e) {
      throw std::invalid_argument(id + ": " + e.what());
    }
    return std::make_unique<PluginEnv>(std::move(env), id);
  };
  // A plugin env lives in this process: built and asked, like the built-in ones.
  entry.spaces = [make = entry.make](const AnyConfig& kwargs) { return spaces_of(*make(kwargs)); };
  entry.params = [factory] {
    ConfigDocumenter documenter;
    ForwardingVisitor<ConfigDocumenter> visitor(documenter);
    api::FieldVisitor* visitors[] = {&visitor};
    factory->make(visitors, false);
    return documenter.rows();
  };
  return entry;
}

// The library of that file name whose envs `registry` holds (loaded by --plugin), or "".
std::string loaded_with_file_name(const Registry& registry, const std::string& file_name) {
  for (const EnvEntry& e : registry.envs())
    if (!e.plugin.empty() && fs::path(e.plugin).filename() == file_name) return e.plugin;
  return "";
}

class HostRegistrar final : public api::Registrar {
 public:
  HostRegistrar(Registry& registry, std::string plugin)
      : registry_(registry), plugin_(std::move(plugin)) {}

  void add_env_factory(const api::EnvSpec& spec,
                       std::unique_ptr<api::EnvFactory> factory) override {
    if (spec.id.empty()) throw std::invalid_argument("an env id must not be empty");
    if (!factory) throw std::invalid_argument("env '" + spec.id + "' has no factory");
    if (const EnvEntry* existing = registry_.find_env(spec.id))
      throw std::invalid_argument(
          "env id '" + spec.id + "' is already registered " +
          (existing->plugin.empty() ? std::string("as a built-in env") : "by " + existing->plugin) +
          ": give the plugin's env another id (e.g. a new -vN suffix)");
    std::shared_ptr<const api::EnvFactory> shared(std::move(factory));
    registry_.add(make_entry(spec, shared, plugin_));
  }

 private:
  Registry& registry_;
  std::string plugin_;
};

}  // namespace

std::string resolve_plugin_path(const std::string& path, const std::string& base_dir) {
  if (path.empty()) throw UsageError("empty plugin path");
  const fs::path p(path);
  const fs::path candidate = p.is_absolute() || base_dir.empty() ? p : fs::path(base_dir) / p;
  std::error_code ec;
  if (fs::is_regular_file(candidate, ec))
    return fs::weakly_canonical(fs::absolute(candidate)).string();
  if (!p.has_parent_path()) return path;  // a bare name: the dynamic loader's search path
  throw UsageError("plugin '" + path + "' not found (looked for " +
                   fs::absolute(candidate).lexically_normal().string() +
                   "); build it first, e.g. `cmake --build build` in the plugin's directory");
}

void register_plugin(PluginEntry entry, const std::string& name, Registry& registry) {
  HostRegistrar registrar(registry, name);
  uint32_t plugin_version = 0;
  try {
    plugin_version = entry(api::kApiVersion, &registrar);
  } catch (const std::exception& e) {
    throw UsageError("plugin " + name + " failed to register its envs: " + e.what());
  }
  if (plugin_version == 1)
    throw UsageError(
        "plugin " + name +
        " was built for rlrun plugin API version 1; this rlrun (" RLRUN_VERSION
        ") implements version " +
        std::to_string(api::kApiVersion) +
        ". Since version 2 there is one env interface for built-in and plugin envs: derive from "
        "rlrun::Env "
        "(#include <rlrun/plugin.hpp>) instead of rlrun::api::Env; use rlrun::Space and "
        "rlrun::StepResult; add `std::string id() const override`, `const Space& "
        "observation_space() const override`, `const Space& action_space() const override` and "
        "`const Info& info() const override` returning your members; replace seed_rng(seed) "
        "and uniform()/integers() by an rlrun::EnvSeeding member (seeding_.on_reset(seed); "
        "seeding_.rng().uniform(...)); then rebuild against this rlrun "
        "(examples/custom_env/go_left.cpp shows the result)");
  if (plugin_version != api::kApiVersion)
    throw UsageError("plugin " + name + " was built for rlrun plugin API version " +
                     std::to_string(plugin_version) +
                     ", but this rlrun (" RLRUN_VERSION ") implements version " +
                     std::to_string(api::kApiVersion) +
                     ": rebuild the plugin against this rlrun's headers (re-run cmake with "
                     "rlrun_DIR pointing at this rlrun's build or install directory)");
}

std::string load_plugin(const std::string& path, Registry& registry) {
  const std::string resolved = resolve_plugin_path(path);
  for (const EnvEntry& e : registry.envs())
    if (e.plugin == resolved) return resolved;  // this registry has it already
  // RTLD_NOW: a missing symbol is reported here, not in the middle of training.
  void* handle = dlopen(resolved.c_str(), RTLD_NOW | RTLD_LOCAL);
  if (!handle) {
    const char* error = dlerror();
    throw UsageError("cannot load plugin " + resolved + ": " + (error ? error : "unknown error"));
  }
  dlerror();
  void* symbol = dlsym(handle, RLRUN_PLUGIN_ENTRY_SYMBOL);
  if (!symbol) {
    dlclose(handle);
    throw UsageError(resolved + " is not an rlrun plugin: it exports no `" +
                     std::string(RLRUN_PLUGIN_ENTRY_SYMBOL) +
                     "` function (define one with RLRUN_PLUGIN from <rlrun/plugin.hpp>)");
  }
  // The handle is never closed: the library's code backs the envs for the life of the process
  // (a second dlopen of the same file, by another registry, returns the same handle).
  register_plugin(reinterpret_cast<PluginEntry>(symbol), resolved, registry);
  return resolved;
}

std::vector<std::string> load_plugins_section(const ConfigNode& plugins, Registry& registry) {
  std::vector<std::string> loaded;
  if (!plugins.defined()) return loaded;
  if (!plugins.is_sequence())
    plugins.fail("expected a list of plugin libraries, e.g. [build/libmyenv.so]");
  const std::string base_dir = plugin_base_dir(plugins);
  for (std::size_t i = 0; i < plugins.size(); ++i) {
    const ConfigNode item = plugins.at(i);
    const std::string path = item.as_string();
    try {
      loaded.push_back(load_plugin(resolve_plugin_path(path, base_dir), registry));
    } catch (const UsageError& e) {
      // A config records where its plugin was; when the library has moved since, a --plugin
      // naming the same file at its new place stands in for it.
      const std::string moved = loaded_with_file_name(registry, fs::path(path).filename().string());
      if (moved.empty()) item.fail(e.what());
      loaded.push_back(moved);
    }
  }
  return loaded;
}

std::string plugin_base_dir(const ConfigNode& plugins) {
  // Relative paths are relative to the experiment file, so configs work from any directory.
  std::error_code ec;
  if (fs::is_regular_file(plugins.origin(), ec))
    return fs::absolute(plugins.origin()).parent_path().string();
  return "";
}

}  // namespace rlrun
