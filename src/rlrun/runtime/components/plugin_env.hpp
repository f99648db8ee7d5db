#pragma once
// A plugin's env as rlrun uses it. Since plugin API v2 a plugin env IS an rlrun::Env (the same
// interface as the built-in envs, include/rlrun/env.hpp), so this wrapper only adds what the
// registry knows and the plugin need not repeat: the registered id. It checks the spaces once
// (a plugin could leave one empty) and forwards everything else, rendering and state included.
#include <memory>
#include <string>

#include "rlrun/env/wrapper.hpp"

namespace rlrun {

class PluginEnv : public Wrapper {
 public:
  // Observations and actions pass unchanged (rlrun export).
  bool exports_unchanged() const override { return true; }
  // Throws std::invalid_argument when the plugin returned no env or an empty space.
  PluginEnv(EnvPtr env, std::string id);
  std::string id() const override { return id_; }

 private:
  std::string id_;
};

}  // namespace rlrun
