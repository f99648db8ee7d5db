#pragma once
#include "rlrun/runtime/registry.hpp"

namespace rlrun {

// The one list of built-in components (DESIGN.md §7). Built once, on first use.
const Registry& builtin_registry();

}  // namespace rlrun
