#pragma once
#include "rlrun/runtime/registry.hpp"

namespace rlrun {

// The one list of built-in components (DESIGN.md §7). Built once, on first use.
const Registry& builtin_registry();
// The same registry, writable: plugins (runtime/plugin_loader.hpp) add their envs to it
// before a config naming them is parsed. Nothing else should change it.
Registry& mutable_builtin_registry();

}  // namespace rlrun
