#pragma once
// The built-in wrappers and algorithms (runtime/components/policy_components.cpp), apart from the envs:
// what reading a model file into a policy needs (rlrun::Policy::load, deploy/).
#include "rlrun/runtime/components/registry.hpp"

namespace rlrun {

// The wrappers usable in `env.wrappers`, applied in order after the Monitor.
void add_builtin_wrappers(Registry& registry);
void add_builtin_algorithms(Registry& registry);

// The wrappers and algorithms alone, unchangeable: a registry without envs, for models loaded
// with ModelEnv::kSpacesOnly from files that record their env's spaces.
const Registry& policy_registry();

}  // namespace rlrun
