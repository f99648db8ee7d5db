#pragma once
// MountainCarContinuous-v0: gymnasium/envs/classic_control/continuous_mountain_car.py
// (Gymnasium 1.0.0). Continuous force in [-1, 1]; +100 at the goal, -0.1 * a^2 every step.
#include <span>
#include <string>

#include "rlrun/envs/classic/classic_control_env.hpp"

namespace rlrun {

class MountainCarContinuous : public ClassicControlEnv {
 public:
  // gymnasium.make("MountainCarContinuous-v0", **kwargs) keyword arguments.
  struct Config {
    // Minimum velocity at the goal position for the episode to terminate.
    double goal_velocity = 0.0;

    template <class V>
    void visit(V& v) {
      v("goal_velocity", goal_velocity, "minimum velocity at the goal for termination");
    }
  };

  // Registered TimeLimit of MountainCarContinuous-v0 (gymnasium/envs/__init__.py).
  static constexpr int kMaxEpisodeSteps = 999;

  // Gymnasium's defaults. (A separate overload because a default argument `= {}` cannot
  // use Config's member initialisers inside the enclosing class.)
  MountainCarContinuous() : MountainCarContinuous(Config{}) {}
  explicit MountainCarContinuous(const Config& config);

  StepResult step(std::span<const float> action, std::span<float> obs) override;
  std::string id() const override { return "MountainCarContinuous-v0"; }
  // continuous_mountain_car.py: screen 600x400, render_fps 30.
  RenderSpec render_spec() const override { return {600, 400, 30}; }

  int state_dim() const override { return 2; }
  void get_state(std::span<double> state) const override;

  const Config& config() const { return config_; }

 protected:
  void sample_initial_state() override;
  void load_state(std::span<const double> state) override;
  void write_observation(std::span<float> obs) const override;
  void draw_state(std::span<const double> state, bool current, Frame& frame) const override;
  void state_from_observation(std::span<const float> obs,
                              std::span<double> state) const override;

 private:
  Config config_;
  // Gymnasium keeps the state as float64 after reset but as a float32 array after every
  // step; both are held here as doubles and rounded to float after each step. set_state
  // keeps the current dtype, like an in-place `env.unwrapped.state[:] = values`.
  double position_ = 0.0;
  double velocity_ = 0.0;
  bool state_is_float32_ = false;
  void write_extra_state(StateWriter& out) const override {
    out.put_bool("state_is_float32", state_is_float32_);
  }
  void read_extra_state(const StateReader& in) override {
    state_is_float32_ = in.get_bool("state_is_float32");
  }
};

}  // namespace rlrun
