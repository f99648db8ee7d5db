#pragma once
// CartPole-v1: gymnasium/envs/classic_control/cartpole.py (Gymnasium 1.0.0), the cart-pole of
// Barto, Sutton & Anderson (1983) with Euler integration, tau = 0.02 s.
#include <array>
#include <span>
#include <string>

#include "rlrun/envs/classic/classic_control_env.hpp"

namespace rlrun {

class CartPole : public ClassicControlEnv {
 public:
  // gymnasium.make("CartPole-v1", **kwargs) keyword arguments.
  struct Config {
    // Reward 0 per step and -1 on (and after) termination instead of +1 per step.
    bool sutton_barto_reward = false;

    template <class V>
    void visit(V& v) {
      v("sutton_barto_reward", sutton_barto_reward,
        "reward 0 per step and -1 at termination (Sutton & Barto) instead of +1 per step");
    }
  };

  // Registered TimeLimit of CartPole-v1 (gymnasium/envs/__init__.py).
  static constexpr int kMaxEpisodeSteps = 500;

  // Gymnasium's defaults. (A separate overload because a default argument `= {}` cannot
  // use Config's member initialisers inside the enclosing class.)
  CartPole() : CartPole(Config{}) {}
  explicit CartPole(const Config& config);

  StepResult step(std::span<const float> action, std::span<float> obs) override;
  std::string id() const override { return "CartPole-v1"; }
  // cartpole.py: screen 600x400, render_fps 50.
  RenderSpec render_spec() const override { return {600, 400, 50}; }

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
  std::array<double, 4> state_{};  // x, x_dot, theta, theta_dot
  // Gymnasium's steps_beyond_terminated: -1 stands for Python's None.
  int steps_beyond_terminated_ = -1;
  void write_extra_state(StateWriter& out) const override {
    out.put_int("steps_beyond_terminated", steps_beyond_terminated_);
  }
  void read_extra_state(const StateReader& in) override {
    steps_beyond_terminated_ = static_cast<int>(in.get_int("steps_beyond_terminated"));
  }
};

}  // namespace rlrun
