#pragma once
// The environment interface: Gymnasium's core.Env (gymnasium/core.py) in C++.
//   reset(seed) writes the first observation; a seed reseeds the env's own RNG, no seed
//   continues its stream (Gymnasium semantics).
//   step(action) writes the next observation and returns reward, terminated, truncated.
//   terminated = the MDP reached a terminal state (never bootstrap from it);
//   truncated  = the episode was cut from outside, e.g. by TimeLimit (bootstrap from it).
// Observations and actions are flat float32 vectors laid out as Space describes; a Discrete
// action is one float holding the integer.
#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <string>

#include "rlrun/core/space.hpp"
#include "rlrun/env/info.hpp"

namespace rlrun {

struct StepResult {
  double reward = 0.0;
  bool terminated = false;
  bool truncated = false;
};

class Frame;  // render/frame.hpp (an RGB canvas); envs that cannot draw ignore it.

class Env {
 public:
  virtual ~Env() = default;

  virtual const Space& observation_space() const = 0;
  virtual const Space& action_space() const = 0;

  virtual void reset(std::optional<uint64_t> seed, std::span<float> obs) = 0;
  virtual StepResult step(std::span<const float> action, std::span<float> obs) = 0;

  // Numeric info of the last reset()/step().
  virtual const Info& info() const = 0;

  // Registered id, e.g. "CartPole-v1".
  virtual std::string id() const = 0;

  // The innermost env (Gymnasium's env.unwrapped).
  virtual Env& unwrapped() { return *this; }
};

using EnvPtr = std::unique_ptr<Env>;

}  // namespace rlrun
