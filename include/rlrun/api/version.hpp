#pragma once
// The version of rlrun's plugin binary interface: everything under include/rlrun/ (the
// classes a plugin compiles against and rlrun calls across the library boundary).
//
// THE ONE PLACE TO BUMP IT: add 1 whenever any header under include/rlrun/ changes in a way
// that changes the binary interface: a virtual function added, removed, reordered or
// changed; a data member of Env, Space, Info, EnvSpec changed; a FieldVisitor overload added.
// rlrun refuses plugins compiled against another version with a message saying to rebuild
// them. tests/runtime/test_plugin_api.cpp keeps a fingerprint of these headers and fails
// when they change without the version (and the fingerprint) being updated.
//
// rlrun's internal Env (src/rlrun/env/env.hpp) is NOT part of this interface: a plugin's env
// is wrapped by rlrun (runtime/plugin_env.hpp), so rendering, resume and other internal
// additions do not break compiled plugins. Exposing such a feature to plugins means adding
// it here, which is a version bump.
#include <cstdint>

#define RLRUN_PLUGIN_API_VERSION 1

namespace rlrun::api {
inline constexpr uint32_t kApiVersion = RLRUN_PLUGIN_API_VERSION;
}  // namespace rlrun::api
