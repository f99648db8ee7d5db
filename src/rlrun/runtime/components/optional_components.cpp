#include "rlrun/runtime/components/optional_components.hpp"

#include <stdexcept>

namespace rlrun {

namespace {

bool is_family(const std::string& id) { return !id.empty() && id.back() == ':'; }

bool names(const std::string& declared, const std::string& id) {
  return is_family(declared) ? id.compare(0, declared.size(), declared) == 0 : id == declared;
}

}  // namespace

const OptionalComponent* unbuilt_component_of(const std::string& id) {
  for (const OptionalComponent& component : optional_components()) {
    if (component.built) continue;
    for (const std::string& declared : component.env_ids)
      if (names(declared, id)) return &component;
  }
  return nullptr;
}

std::string unbuilt_env_message(const std::string& id, const OptionalComponent& component) {
  return id + " is not built into this rlrun (" + component.description +
         " were left out): install Debian's " + component.packages + ", then configure with -D" +
         component.option + "=ON and build again (docs/install.md)";
}

// The entry is a family of one id (or of the family's ids): Registry::env expands it when a
// config names the id, and the expansion's refusal is reported at the config's env.id.
void add_unbuilt_env_entries(EnvEntries& out) {
  for (const OptionalComponent& component : optional_components()) {
    if (component.built) continue;
    for (const std::string& id : component.env_ids) {
      EnvEntry entry;
      entry.id = id;
      entry.description =
          "(not built: -D" + component.option + "=ON, Debian's " + component.packages + ")";
      entry.params = [] { return std::vector<FieldDoc>{}; };
      entry.expand = [&component](const std::string& named) -> EnvEntry {
        throw std::invalid_argument(unbuilt_env_message(named, component));
      };
      out.push_back(std::move(entry));
    }
  }
}

}  // namespace rlrun
