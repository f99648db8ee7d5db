#pragma once
// Shared base of the five classic-control envs (gymnasium/envs/classic_control/*.py).
// It owns what they all have in common: the two spaces, the env's own Rng with Gymnasium's
// seeding rules, an (empty) Info, and a flat float64 physical state that tests can read and
// overwrite the way Gymnasium code does with `env.unwrapped.state = ...`. The reference
// replay (tests/envs/test_gym_reference.cpp) relies on that to start every recorded episode
// from exactly the state Gymnasium had.
#include <cstdint>
#include <optional>
#include <span>

#include "rlrun/rng.hpp"
#include "rlrun/space.hpp"
#include "rlrun/env.hpp"
#include "rlrun/env_seeding.hpp"
#include "rlrun/info.hpp"

namespace rlrun {

class ClassicControlEnv : public Env {
 public:
  const Space& observation_space() const override { return observation_space_; }
  const Space& action_space() const override { return action_space_; }
  const Info& info() const override { return info_; }

  // gymnasium/core.py Env.reset(seed=...): a seed reseeds the env's Rng; no seed continues
  // its stream, except that the very first reset without any seed draws one from
  // std::random_device (Gymnasium seeds np_random from OS entropy in that case).
  void reset(std::optional<uint64_t> seed, std::span<float> obs) final;

  // Number of float64 values in the physical state (CartPole 4, Pendulum 2, ...).
  virtual int state_dim() const = 0;
  // Copies the physical state, in Gymnasium's `env.unwrapped.state` order, into `state`.
  virtual void get_state(std::span<double> state) const = 0;
  // Equivalent of Gymnasium's `env.unwrapped.state[:] = state` followed by reading the
  // observation the env would return for it. Only the state changes (no RNG draw, no episode
  // bookkeeping), and the values keep the dtype Gymnasium's state array has at that moment:
  // Acrobot's is float32 right after reset(), MountainCarContinuous's is float32 after a
  // step, all others are float64. Throws std::invalid_argument on a wrong size.
  void set_state(std::span<const double> state, std::span<float> obs);

  Rng& rng() { return seeding_.rng(); }

  // Rendering (Gymnasium's render_mode="rgb_array", drawn like its pygame code; the drawing
  // of each env lives in <env>_render.cpp). render() draws the current state and throws
  // std::logic_error before the first reset(); render_observation() draws the state an
  // observation describes (all five observations determine the picture).
  bool render(Frame& frame) const override;
  bool render_observation(std::span<const float> obs, Frame& frame) const override;

  // Resume: the Rng, the seeding/reset flags, the physical state and each env's extra
  // bookkeeping (write_extra_state), so a restored env continues bit-identically.
  bool can_save_state() const override { return true; }
  void write_state(StateWriter& out) const override;
  void read_state(const StateReader& in) override;

 protected:
  ClassicControlEnv(Space observation_space, Space action_space);

  // Draws the initial state from rng() (the env's reset() body after super().reset()).
  virtual void sample_initial_state() = 0;
  // Overwrites the physical state; `state.size() == state_dim()` is checked by the caller.
  virtual void load_state(std::span<const double> state) = 0;
  // Writes the float32 observation of the current state.
  virtual void write_observation(std::span<float> obs) const = 0;
  // Draws a physical state (state_dim() values, get_state() order) into `frame`. `current`
  // says it is the env's own current state, so extras such as Pendulum's last-torque arrow
  // may be drawn too (an observation does not carry them).
  virtual void draw_state(std::span<const double> state, bool current, Frame& frame) const = 0;
  // The physical state an observation describes, as far as drawing needs it.
  virtual void state_from_observation(std::span<const float> obs,
                                      std::span<double> state) const = 0;
  // State beyond the physical state vector (e.g. CartPole's steps_beyond_terminated).
  virtual void write_extra_state(StateWriter& /*out*/) const {}
  virtual void read_extra_state(const StateReader& /*in*/) {}

  // Throws std::logic_error when step() runs before the first reset() (Gymnasium asserts).
  void require_reset() const;
  // Reads a Discrete(n) action as an index and throws std::invalid_argument when the action
  // space does not contain it (Gymnasium asserts `action_space.contains(action)`).
  int discrete_action(std::span<const float> action) const;

  Space observation_space_;
  Space action_space_;
  Info info_;

 private:
  EnvSeeding seeding_;
  bool has_state_ = false;
};

}  // namespace rlrun
