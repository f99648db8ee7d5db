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

#include "rlrun/core/rng.hpp"
#include "rlrun/core/space.hpp"
#include "rlrun/env/env.hpp"
#include "rlrun/env/info.hpp"

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

  Rng& rng() { return rng_; }

 protected:
  ClassicControlEnv(Space observation_space, Space action_space);

  // Draws the initial state from rng_ (the env's reset() body after super().reset()).
  virtual void sample_initial_state() = 0;
  // Overwrites the physical state; `state.size() == state_dim()` is checked by the caller.
  virtual void load_state(std::span<const double> state) = 0;
  // Writes the float32 observation of the current state.
  virtual void write_observation(std::span<float> obs) const = 0;

  // Throws std::logic_error when step() runs before the first reset() (Gymnasium asserts).
  void require_reset() const;
  // Reads a Discrete(n) action as an index and throws std::invalid_argument when the action
  // space does not contain it (Gymnasium asserts `action_space.contains(action)`).
  int discrete_action(std::span<const float> action) const;

  Space observation_space_;
  Space action_space_;
  Info info_;
  Rng rng_;

 private:
  bool ever_seeded_ = false;
  bool has_state_ = false;
};

}  // namespace rlrun
