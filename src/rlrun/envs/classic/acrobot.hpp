#pragma once
// Acrobot-v1: gymnasium/envs/classic_control/acrobot.py (Gymnasium 1.0.0), Sutton's two-link
// under-actuated robot ("book" dynamics of Sutton & Barto 1998), integrated with one RK4 step
// of dt = 0.2 s. Torque noise is 0 as in Gymnasium, so the env draws randomness only in reset.
#include <array>
#include <span>
#include <string>

#include "rlrun/envs/classic/classic_control_env.hpp"

namespace rlrun {

class Acrobot : public ClassicControlEnv {
 public:
  // gymnasium.make("Acrobot-v1") takes no keyword arguments besides render_mode.
  struct Config {
    template <class V>
    void visit(V&) {}
  };

  // Registered TimeLimit of Acrobot-v1 (gymnasium/envs/__init__.py).
  static constexpr int kMaxEpisodeSteps = 500;

  // Gymnasium's defaults. (A separate overload because a default argument `= {}` cannot
  // use Config's member initialisers inside the enclosing class.)
  Acrobot() : Acrobot(Config{}) {}
  explicit Acrobot(const Config& config);

  StepResult step(std::span<const float> action, std::span<float> obs) override;
  std::string id() const override { return "Acrobot-v1"; }
  // acrobot.py: SCREEN_DIM 500, render_fps 15.
  RenderSpec render_spec() const override { return {500, 500, 15}; }

  int state_dim() const override { return 4; }
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
  std::array<double, 4> state_{};  // theta1, theta2, dtheta1, dtheta2
  // Gymnasium's state array is float32 right after reset() (`.astype(np.float32)`) and
  // float64 after a step (rk4 returns float64); set_state keeps that dtype, like an in-place
  // `env.unwrapped.state[:] = values` does.
  bool state_is_float32_ = false;
  void write_extra_state(StateWriter& out) const override {
    out.put_bool("state_is_float32", state_is_float32_);
  }
  void read_extra_state(const StateReader& in) override {
    state_is_float32_ = in.get_bool("state_is_float32");
  }
};

}  // namespace rlrun
