#pragma once
// rlrun's plugin API: write environments in C++ and train on them with the rlrun binary,
// without recompiling rlrun (examples/custom_env/README.md walks through it).
//
//   #include <rlrun/plugin.hpp>
//   class MyEnv : public rlrun::EnvBase { ... };            // rlrun/env_base.hpp, on
//                                                           // rlrun::Env: the interface of
//                                                           // rlrun's own envs
//   RLRUN_PLUGIN(registrar) {
//     registrar.add_env<MyEnv>("MyEnv-v0", "what it is", 200);
//   }
//
// Build it as a shared library (CMake: find_package(rlrun), then rlrun_add_plugin(name
// sources...)) and load it with `rlrun train|eval|check-env --plugin libmyenv.so` or a
// `plugins: [libmyenv.so]` list in the experiment file. An env that draws itself (render())
// includes <rlrun/frame.hpp> and links Cairo; one that saves its state (write_state /
// read_state) is resumed exactly and its checkpoints are full ones.
//
// The binary contract, fixed for all versions: the library exports one C function,
//   uint32_t rlrun_plugin_register(uint32_t host_api_version, rlrun::api::Registrar* r);
// rlrun calls it with its own RLRUN_PLUGIN_API_VERSION; the plugin registers its envs only
// when that equals the version it was compiled with, and always returns its version, so
// rlrun can refuse a mismatch with a clear message before any C++ object crosses over.
#include <cstdint>

#include "rlrun/config.hpp"
#include "rlrun/env.hpp"
#include "rlrun/env_base.hpp"
#include "rlrun/env_seeding.hpp"
#include "rlrun/info.hpp"
#include "rlrun/registrar.hpp"
#include "rlrun/space.hpp"
#include "rlrun/state.hpp"
#include "rlrun/version.hpp"

// The name rlrun looks up in a plugin library.
#define RLRUN_PLUGIN_ENTRY_SYMBOL "rlrun_plugin_register"

// Defines the plugin's registration function; the block that follows is its body, with
// `registrar_name` a rlrun::api::Registrar&.
#define RLRUN_PLUGIN(registrar_name)                                                \
  static void rlrun_plugin_register_envs(::rlrun::api::Registrar& registrar_name);  \
  extern "C" __attribute__((visibility("default"))) uint32_t rlrun_plugin_register( \
      uint32_t host_api_version, ::rlrun::api::Registrar* host) {                   \
    if (host_api_version == RLRUN_PLUGIN_API_VERSION && host != nullptr)            \
      rlrun_plugin_register_envs(*host);                                            \
    return RLRUN_PLUGIN_API_VERSION;                                                \
  }                                                                                 \
  static void rlrun_plugin_register_envs(::rlrun::api::Registrar& registrar_name)
