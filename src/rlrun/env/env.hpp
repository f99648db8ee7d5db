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
#include <stdexcept>
#include <string>

#include "rlrun/core/space.hpp"
#include "rlrun/core/state_dict.hpp"
#include "rlrun/env/info.hpp"

namespace rlrun {

struct StepResult {
  double reward = 0.0;
  bool terminated = false;
  bool truncated = false;
};

class Frame;  // render/frame.hpp (an RGB canvas); envs that cannot draw ignore it.

// How an env likes to be drawn: Gymnasium's screen size and metadata["render_fps"].
// width == 0 means the env cannot render.
struct RenderSpec {
  int width = 0;
  int height = 0;
  double fps = 30.0;
};

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

  // Exact resume (checkpoints): write_state() saves everything the next reset()/step()
  // depends on beyond the constructor's configuration (physical state, RNG, episode
  // counters); read_state() restores it into an env built from the same configuration.
  // Envs that cannot snapshot themselves (an external simulator) keep can_save_state()
  // false: a resumed run then starts them with fresh episodes, and the trainer says so.
  virtual bool can_save_state() const { return false; }
  virtual void write_state(StateWriter& /*out*/) const {
    throw std::logic_error(id() + " cannot save its state for resume");
  }
  virtual void read_state(const StateReader& /*in*/) {
    throw std::logic_error(id() + " cannot restore a saved state");
  }

  // Rendering (Gymnasium's render_mode="rgb_array"). render() draws the current state into
  // `frame`, scaled to the frame's size; it returns false when the env cannot draw.
  // render_observation() draws the state an observation describes (for envs whose
  // observation determines the picture), so logged observations can be turned into video.
  virtual RenderSpec render_spec() const { return {}; }
  virtual bool render(Frame& /*frame*/) const { return false; }
  virtual bool render_observation(std::span<const float> /*obs*/, Frame& /*frame*/) const {
    return false;
  }
};

using EnvPtr = std::unique_ptr<Env>;

}  // namespace rlrun
