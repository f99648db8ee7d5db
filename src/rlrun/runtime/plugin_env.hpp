#pragma once
// The adapter between a plugin's env (rlrun::api::Env, include/rlrun/api/env.hpp: the
// versioned binary interface plugins compile against) and rlrun's own Env interface. It
// converts the spaces once, forwards reset/step, and mirrors the plugin's info keys and
// values into an rlrun Info. Everything rlrun's Env has beyond the plugin API (resume state,
// rendering) keeps Env's defaults here, so internal additions never break compiled plugins.
#include <memory>
#include <string>
#include <vector>

#include "rlrun/api/env.hpp"
#include "rlrun/env/env.hpp"

namespace rlrun {

// Converts a plugin's space, throwing std::invalid_argument naming `what` when it is not a
// valid space (e.g. Box low > high, Discrete n <= 0).
Space space_from_api(const api::Space& space, const std::string& what);

class PluginEnv : public Env {
 public:
  // Throws std::invalid_argument when the plugin env's spaces are invalid.
  PluginEnv(std::unique_ptr<api::Env> env, std::string id);

  const Space& observation_space() const override { return observation_space_; }
  const Space& action_space() const override { return action_space_; }
  void reset(std::optional<uint64_t> seed, std::span<float> obs) override;
  StepResult step(std::span<const float> action, std::span<float> obs) override;
  const Info& info() const override { return info_; }
  std::string id() const override { return id_; }

  api::Env& plugin_env() { return *env_; }

 private:
  void copy_info();

  std::unique_ptr<api::Env> env_;
  std::string id_;
  Space observation_space_;
  Space action_space_;
  Info info_;
  std::vector<int> index_;  // plugin info key i -> info_ index
};

}  // namespace rlrun
