#pragma once
// MountainCar-v0: gymnasium/envs/classic_control/mountain_car.py (Gymnasium 1.0.0), Moore's
// (1990) under-powered car in a valley; 3 discrete actions (push left, none, push right).
#include <span>
#include <string>

#include "rlrun/envs/classic/classic_control_env.hpp"

namespace rlrun {

class MountainCar : public ClassicControlEnv {
 public:
  // gymnasium.make("MountainCar-v0", **kwargs) keyword arguments.
  struct Config {
    // Minimum velocity at the goal position for the episode to terminate.
    double goal_velocity = 0.0;

    template <class V>
    void visit(V& v) {
      v("goal_velocity", goal_velocity, "minimum velocity at the goal for termination");
    }
  };

  // Registered TimeLimit of MountainCar-v0 (gymnasium/envs/__init__.py).
  static constexpr int kMaxEpisodeSteps = 200;

  // Gymnasium's defaults. (A separate overload because a default argument `= {}` cannot
  // use Config's member initialisers inside the enclosing class.)
  MountainCar() : MountainCar(Config{}) {}
  explicit MountainCar(const Config& config);

  StepResult step(std::span<const float> action, std::span<float> obs) override;
  std::string id() const override { return "MountainCar-v0"; }
  // mountain_car.py: screen 600x400, render_fps 30.
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
  double position_ = 0.0;
  double velocity_ = 0.0;
};

}  // namespace rlrun
