#pragma once
// Base wrapper (gymnasium.Wrapper): owns the inner env and forwards everything; subclasses
// override only what they change.
#include <utility>

#include "rlrun/env/env.hpp"

namespace rlrun {

class Wrapper : public Env {
 public:
  explicit Wrapper(EnvPtr inner) : inner_(std::move(inner)) {}

  const Space& observation_space() const override { return inner_->observation_space(); }
  const Space& action_space() const override { return inner_->action_space(); }
  void reset(std::optional<uint64_t> seed, std::span<float> obs) override {
    inner_->reset(seed, obs);
  }
  StepResult step(std::span<const float> action, std::span<float> obs) override {
    return inner_->step(action, obs);
  }
  const Info& info() const override { return inner_->info(); }
  std::string id() const override { return inner_->id(); }
  Env& unwrapped() override { return inner_->unwrapped(); }

  Env& inner() { return *inner_; }

 protected:
  EnvPtr inner_;
};

}  // namespace rlrun
