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
// Version 3: Space gained a Box dtype (float32 or uint8, BoxDtype) and Tensor's DType uint8.
// Version 2: plugin envs derive from rlrun::Env (rlrun/env.hpp), the very interface of rlrun's
// built-in envs, with rendering, state save/restore and the multi-agent step; Space, Info,
// Rng, EnvSeeding, the saved-state classes and Frame are rlrun's own (header-only).
// Version 1 had a separate rlrun::api::Env with its own Space and Info.
#include <cstdint>

#define RLRUN_PLUGIN_API_VERSION 3

namespace rlrun::api {
inline constexpr uint32_t kApiVersion = RLRUN_PLUGIN_API_VERSION;
}  // namespace rlrun::api
