#pragma once
// CartPole-v1: gymnasium/envs/classic_control/cartpole.py (Gymnasium 1.0.0), the cart-pole of
// Barto, Sutton & Anderson (1983) with Euler integration, tau = 0.02 s.
#include <array>
#include <span>
#include <string>

#include "rlrun/envs/classic/classic_control_env.hpp"

namespace rlrun {

// gymnasium.make("CartPole-v1", **kwargs) keyword arguments.
struct CartPoleConfig {
  // Reward 0 per step and -1 on (and after) termination instead of +1 per step.
  bool sutton_barto_reward = false;

  template <class V>
  void visit(V& v) {
    v("sutton_barto_reward", sutton_barto_reward,
      "reward 0 per step and -1 at termination (Sutton & Barto) instead of +1 per step");
  }
};

// The state is x, x_dot, theta, theta_dot.
class CartPole : public ClassicControlEnv {
 public:
  using Config = CartPoleConfig;
  static constexpr int kMaxEpisodeSteps = 500;  // registered TimeLimit (gymnasium/envs/__init__.py)

  explicit CartPole(const Config& config = {});
  StepResult step(std::span<const float> action, std::span<float> obs) override;

 private:
  Config config_;
  // Gymnasium's steps_beyond_terminated: -1 stands for Python's None.
  int steps_beyond_terminated_ = -1;
  void reset_bookkeeping() override { steps_beyond_terminated_ = -1; }
  void write_extra_state(StateWriter& out) const override {
    out.put_int("steps_beyond_terminated", steps_beyond_terminated_);
  }
  void read_extra_state(const StateReader& in) override {
    steps_beyond_terminated_ =
        static_cast<int>(in.get_int_in("steps_beyond_terminated", -1, INT_MAX));
  }
};

}  // namespace rlrun
