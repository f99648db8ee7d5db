#pragma once
// An env known by its spaces alone (env/env_spaces.hpp): the bottom of a wrapper stack that is
// built to learn the spaces the agent sees (experiment parsing) or to turn a model into a
// policy (predict, export), never to be stepped. reset() and step() throw std::logic_error:
// reaching them is a bug in rlrun, not a user's mistake. It declares no info keys.
#include <stdexcept>
#include <string>
#include <utility>

#include "rlrun/env.hpp"
#include "rlrun/env/env_spaces.hpp"

namespace rlrun {

class SpacesOnlyEnv : public Env {
 public:
  SpacesOnlyEnv(std::string id, EnvSpaces spaces)
      : id_(std::move(id)), spaces_(std::move(spaces)) {}

  const Space& observation_space() const override { return spaces_.observation; }
  const Space& action_space() const override { return spaces_.action; }
  int num_agents() const override { return spaces_.num_agents; }
  std::string id() const override { return id_; }
  // The env's render size (a wrapper's space may depend on it); it draws nothing.
  RenderSpec render_spec() const override { return spaces_.render; }
  const Info& info() const override { return info_; }

  void reset(std::optional<uint64_t> /*seed*/, std::span<float> /*obs*/) override {
    not_runnable();
  }
  StepResult step(std::span<const float> /*action*/, std::span<float> /*obs*/) override {
    not_runnable();
  }
  void step_agents(std::span<const float> /*actions*/, std::span<float> /*obs*/,
                   std::span<StepResult> /*results*/) override {
    not_runnable();
  }

 private:
  [[noreturn]] void not_runnable() const {
    throw std::logic_error(id_ + ": this env stands for its spaces only and cannot be stepped");
  }

  std::string id_;
  EnvSpaces spaces_;
  Info info_;
};

}  // namespace rlrun
