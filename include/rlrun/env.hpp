#pragma once
// The environment interface: Gymnasium's core.Env (gymnasium/core.py) in C++. rlrun's built-in
// envs, plugin envs (rlrun/plugin.hpp) and bridged envs all derive from this one class, so
// everything rlrun does with an env (train, evaluate, record video, resume exactly) works the
// same for all of them. It is the plugin binary interface: changing it is a version bump
// (rlrun/version.hpp).
//
//   reset(seed) writes the first observation; a seed reseeds the env's own RNG, no seed
//   continues its stream (Gymnasium semantics; EnvSeeding in rlrun/env_seeding.hpp does it).
//   step(action) writes the next observation and returns reward, terminated, truncated.
//   terminated = the MDP reached a terminal state (never bootstrap from it);
//   truncated  = the episode was cut from outside, e.g. by TimeLimit (bootstrap from it).
// Observations and actions are flat float32 vectors laid out as their Space describes
// (rlrun/space.hpp); a Discrete action is one float holding the integer.
//
// Several agents (PettingZoo's parallel API, pettingzoo/utils/env.py ParallelEnv, with
// identical agents that share one policy, as sumo-rl's traffic lights do): num_agents() > 1,
// observation_space() and action_space() are ONE agent's, and the env implements
// step_agents(): actions and observations are agent-major (agent i's floats at
// [i * dim, (i + 1) * dim)), and every agent gets its own reward and flags each step. reset()
// writes every agent's first observation. An episode ends when all agents are terminated or
// truncated at the same step (agents are not removed one by one); rlrun's VecEnv then treats
// each agent as one env column of a shared policy (parameter sharing, as SuperSuit's
// pettingzoo_env_to_vec_env does for SB3).
#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <stdexcept>
#include <string>

#include "rlrun/info.hpp"
#include "rlrun/space.hpp"
#include "rlrun/state.hpp"

namespace rlrun {

struct StepResult {
  double reward = 0.0;
  bool terminated = false;
  bool truncated = false;
};

class Frame;  // rlrun/frame.hpp (an RGB canvas); envs that cannot draw ignore it.

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

  // Numeric info of the last reset()/step() (e.g. `is_success`).
  virtual const Info& info() const = 0;

  // Registered id, e.g. "CartPole-v1".
  virtual std::string id() const = 0;

  // The innermost env (Gymnasium's env.unwrapped).
  virtual Env& unwrapped() { return *this; }

  // Multi-agent envs (see above). A single-agent env keeps these defaults.
  virtual int num_agents() const { return 1; }
  // `results` has num_agents() entries.
  virtual void step_agents(std::span<const float> actions, std::span<float> obs,
                           std::span<StepResult> results) {
    results[0] = step(actions, obs);
  }

  // Exact resume (checkpoints): write_state() saves everything the next reset()/step()
  // depends on beyond the constructor's configuration (physical state, RNG, episode
  // counters); read_state() restores it into an env built from the same configuration.
  // Envs that cannot snapshot themselves (an external simulator) keep can_save_state()
  // false: checkpoints then hold the model only, and `--resume` refuses them with the reason.
  virtual bool can_save_state() const { return false; }
  virtual void write_state(StateWriter& /*out*/) const {
    throw std::logic_error(id() + " cannot save its state for resume");
  }
  virtual void read_state(const StateReader& /*in*/) {
    throw std::logic_error(id() + " cannot restore a saved state");
  }

  // Rendering (Gymnasium's render_mode="rgb_array"). render() draws the current state into
  // `frame` (rlrun/frame.hpp), scaled to the frame's size; it returns false when the env
  // cannot draw. render_observation() draws the state an observation describes (for envs
  // whose observation determines the picture), so logged observations can become video.
  virtual RenderSpec render_spec() const { return {}; }
  virtual bool render(Frame& /*frame*/) const { return false; }
  virtual bool render_observation(std::span<const float> /*obs*/, Frame& /*frame*/) const {
    return false;
  }
};

using EnvPtr = std::unique_ptr<Env>;

}  // namespace rlrun
