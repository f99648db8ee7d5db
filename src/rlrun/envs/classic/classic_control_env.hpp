#pragma once
// Shared base of the five classic-control envs (gymnasium/envs/classic_control/*.py).
// It owns what they all have in common: the two spaces, the env's own np_random with
// Gymnasium's seeding rules and numpy's stream (env/gymnasium_seeding.hpp: reset(seed=s) draws
// Gymnasium's initial state for s), an (empty) Info, the id and picture size, and the flat float64 physical state
// (`state_`, in Gymnasium's `env.unwrapped.state` order) that tests can read and overwrite the
// way Gymnasium code does with `env.unwrapped.state = ...`. The reference replay
// (tests/envs/test_gym_reference.cpp) relies on that to start every recorded episode from
// exactly the state Gymnasium had. An env adds its physics: the initial state, step() and the
// observation of a state; its picture is a pair of functions in <env>_render.cpp.
#include <array>
#include <cstdint>
#include <limits>
#include <optional>
#include <span>
#include <string>

#include "rlrun/env.hpp"
#include "rlrun/env/gymnasium_seeding.hpp"
#include "rlrun/env/numpy_random.hpp"
#include "rlrun/info.hpp"
#include "rlrun/space.hpp"

namespace rlrun {

// What tells one classic env from another besides its physics.
struct ClassicSpec {
  const char* id;     // e.g. "CartPole-v1"
  RenderSpec render;  // Gymnasium's screen size and render_fps
  int state_dim;      // values in the physical state (CartPole 4, Pendulum 2, ...)
  // Gymnasium's state array is float32 at times (Acrobot right after reset(),
  // MountainCarContinuous after a step): such envs track the dtype, saved with the state.
  bool tracks_float32_state;
  // The reset() body after super().reset(): the initial state drawn from the env's np_random;
  // returns whether Gymnasium holds it as float32.
  bool (*initial_state)(NumpyRandom& np_random, std::span<double> state);
  // The float32 observation of a state.
  void (*observation)(std::span<const double> state, std::span<float> obs);
  // The picture of a state (Gymnasium's render(), <env>_render.cpp); `last_action` is the
  // env's last action when the state is its current one (Pendulum draws its torque), else NaN.
  void (*draw)(std::span<const double> state, double last_action, Frame& frame);
  // The physical state an observation describes, as far as drawing needs it.
  void (*state_from_observation)(std::span<const float> obs, std::span<double> state);
};

class ClassicControlEnv : public Env {
 public:
  static constexpr int kMaxStateDim = 4;

  const Space& observation_space() const override { return observation_space_; }
  const Space& action_space() const override { return action_space_; }
  const Info& info() const override { return info_; }
  std::string id() const override { return spec_.id; }
  RenderSpec render_spec() const override { return spec_.render; }

  // gymnasium/core.py Env.reset(seed=...): a seed reseeds the env's np_random; no seed
  // continues its stream, except that the very first reset without any seed draws one from
  // std::random_device (Gymnasium seeds np_random from OS entropy in that case).
  void reset(std::optional<uint64_t> seed, std::span<float> obs) final;

  int state_dim() const { return spec_.state_dim; }
  // Copies the physical state, in Gymnasium's `env.unwrapped.state` order, into `state`.
  void get_state(std::span<double> state) const;
  // Equivalent of Gymnasium's `env.unwrapped.state[:] = state` followed by reading the
  // observation the env would return for it. Only the state changes (no RNG draw, no episode
  // bookkeeping), and the values keep the dtype Gymnasium's state array has at that moment
  // (float32 or float64, see ClassicSpec). Throws std::invalid_argument on a wrong size.
  void set_state(std::span<const double> state, std::span<float> obs);

  NumpyRandom& np_random() { return seeding_.random(); }

  // Rendering (Gymnasium's render_mode="rgb_array", drawn like its pygame code). render()
  // draws the current state and throws std::logic_error before the first reset();
  // render_observation() draws the state an observation describes (all five observations
  // determine the picture).
  bool render(Frame& frame) const override;
  bool render_observation(std::span<const float> obs, Frame& frame) const override;

  // Resume: np_random, the seeding/reset flags, the physical state (and its dtype) and each
  // env's extra bookkeeping (write_extra_state), so a restored env continues bit-identically.
  bool can_save_state() const override { return true; }
  void write_state(StateWriter& out) const override;
  void read_state(const StateReader& in) override;

 protected:
  ClassicControlEnv(const ClassicSpec& spec, Space observation_space, Space action_space);

  // Writes the float32 observation of the current state.
  void write_observation(std::span<float> obs) const {
    spec_.observation(std::span<const double>(state_.data(), static_cast<size_t>(state_dim())),
                      obs);
  }
  // Episode bookkeeping beyond the state that reset() starts anew (e.g. CartPole's
  // steps_beyond_terminated).
  virtual void reset_bookkeeping() {}
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
  // The physical state: the first spec.state_dim values, in Gymnasium's order.
  std::array<double, kMaxStateDim> state_{};
  bool state_is_float32_ = false;  // see ClassicSpec::tracks_float32_state
  double last_action_ = std::numeric_limits<double>::quiet_NaN();  // for the picture only

 private:
  ClassicSpec spec_;
  GymnasiumSeeding seeding_;
  bool has_state_ = false;
};

}  // namespace rlrun
