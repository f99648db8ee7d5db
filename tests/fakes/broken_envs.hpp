#pragma once
// Deliberately broken envs for check_env: each breaks exactly one rule the checker enforces.
// All derive from BrokenEnvBase, a small random-walk env that is otherwise correct.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>
#include <random>
#include <span>
#include <stdexcept>
#include <string>

#include "rlrun/env.hpp"
#include "rlrun/rng.hpp"

namespace rlrun::testing {

// A correct env: obs = 2 values in [-1, 1] drawn at reset, nudged by the action at each step,
// episodes of 5 steps (truncated).
class BrokenEnvBase : public Env {
 public:
  const Space& observation_space() const override { return observation_space_; }
  const Space& action_space() const override { return action_space_; }
  const Info& info() const override { return info_; }
  std::string id() const override { return "Walk-v0"; }

  void reset(std::optional<uint64_t> seed, std::span<float> obs) override {
    if (seed) rng_.reseed(*seed);
    steps_ = 0;
    x_ = static_cast<float>(rng_.uniform(-0.5, 0.5));
    y_ = static_cast<float>(rng_.uniform(-0.5, 0.5));
    write(obs);
  }
  StepResult step(std::span<const float> action, std::span<float> obs) override {
    ++steps_;
    x_ = std::clamp(x_ + 0.1f * (action[0] - 0.5f), -1.0f, 1.0f);
    write(obs);
    return {static_cast<double>(x_), false, steps_ >= 5};
  }

 protected:
  void write(std::span<float> obs) const {
    obs[0] = x_;
    obs[1] = y_;
  }
  Space observation_space_ = Space::box(-1.0f, 1.0f, {2});
  Space action_space_ = Space::discrete(2);
  Info info_;
  Rng rng_;
  float x_ = 0, y_ = 0;
  int steps_ = 0;
};

// Writes an observation outside its Box after the second step.
class ObsOutOfSpaceEnv : public BrokenEnvBase {
 public:
  StepResult step(std::span<const float> action, std::span<float> obs) override {
    StepResult r = BrokenEnvBase::step(action, obs);
    if (steps_ >= 2) obs[1] = 3.0f;
    return r;
  }
};

// Ignores the seed: always draws from its own entropy-seeded stream.
class SeedIgnoringEnv : public BrokenEnvBase {
 public:
  void reset(std::optional<uint64_t>, std::span<float> obs) override {
    BrokenEnvBase::reset(std::random_device{}(), obs);
  }
};

// Ignores the seed in a subtler way: reseeds with a constant, so every seed looks the same.
class ConstantSeedEnv : public BrokenEnvBase {
 public:
  void reset(std::optional<uint64_t> seed, std::span<float> obs) override {
    BrokenEnvBase::reset(seed ? std::optional<uint64_t>(42) : std::nullopt, obs);
  }
};

// Steps depend on hidden state that reset() does not restore.
class NondeterministicStepEnv : public BrokenEnvBase {
 public:
  StepResult step(std::span<const float> action, std::span<float> obs) override {
    StepResult r = BrokenEnvBase::step(action, obs);
    obs[0] = std::clamp(obs[0] + 1e-3f * static_cast<float>(++calls_ % 7), -1.0f, 1.0f);
    return r;
  }

 private:
  int calls_ = 0;
};

// Returns NaN rewards.
class NanRewardEnv : public BrokenEnvBase {
 public:
  StepResult step(std::span<const float> action, std::span<float> obs) override {
    StepResult r = BrokenEnvBase::step(action, obs);
    r.reward = std::numeric_limits<double>::quiet_NaN();
    return r;
  }
};

// Cannot start a second episode: reset() after an episode ended throws.
class NoSecondEpisodeEnv : public BrokenEnvBase {
 public:
  void reset(std::optional<uint64_t> seed, std::span<float> obs) override {
    if (ended_) throw std::runtime_error("simulator died after the first episode");
    BrokenEnvBase::reset(seed, obs);
  }
  StepResult step(std::span<const float> action, std::span<float> obs) override {
    StepResult r = BrokenEnvBase::step(action, obs);
    ended_ = ended_ || r.terminated || r.truncated;
    return r;
  }

 private:
  bool ended_ = false;
};

// Correct, but its start state never varies (like a fixed maze): must NOT be flagged.
class FixedStartEnv : public BrokenEnvBase {
 public:
  void reset(std::optional<uint64_t> seed, std::span<float> obs) override {
    BrokenEnvBase::reset(seed, obs);
    x_ = 0.25f;
    y_ = -0.25f;
    write(obs);
  }
};

}  // namespace rlrun::testing
