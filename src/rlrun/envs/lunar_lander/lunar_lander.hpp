#pragma once
// LunarLander-v3: gymnasium/envs/box2d/lunar_lander.py (Gymnasium 1.0.0), by
// Oleg Klimov, on Debian's Box2D 2.4 (Gymnasium runs pybox2d 2.3; docs/box2d.md
// says what that changes: the rules, constants, spaces and rewards are
// Gymnasium's, trajectories are not bit-equal).
//
//   observation  Box(8): x, y (pad-relative, scaled), vx, vy (scaled), angle,
//   angular
//                velocity (scaled), left leg contact, right leg contact (0/1)
//   action       Discrete(4): 0 nothing, 1 left engine, 2 main engine, 3 right
//   engine;
//                with continuous: Box(-1, 1, (2,)): main throttle, lateral
//                throttle
//   reward       difference of the shaping -100*dist -100*speed -100*|angle|
//   +10 per leg on
//                the ground, minus 0.3 per main-engine frame and 0.03 per
//                side-engine frame (scaled by throttle); -100 on a crash or
//                leaving |x| >= 1, +100 at rest
//   termination  body contact with the moon, |x| >= 1, or the lander falls
//   asleep (at rest)
//
// Gymnasium's exhaust particles are Box2D bodies that collide with the ground
// only and, since Gymnasium 1.0, exist only when rendering ("particles are just
// a decoration, with no impact on the physics"): they never touch the lander,
// so rlrun leaves them out (docs/box2d.md).
#include <array>
#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <string>

#include "rlrun/env.hpp"
#include "rlrun/env_seeding.hpp"
#include "rlrun/info.hpp"
#include "rlrun/space.hpp"

namespace rlrun {

// gymnasium.make("LunarLander-v3", **kwargs) keyword arguments
// (LunarLander.__init__).
struct LunarLanderConfig {
  bool continuous = false;        // Box(-1, 1, (2,)) throttles instead of Discrete(4)
  double gravity = -10.0;         // must lie in (-12, 0)
  bool enable_wind = false;       // wind force and turbulence torque while no leg touches
  double wind_power = 15.0;       // max wind force (recommended 0..20)
  double turbulence_power = 1.5;  // max turbulence torque (recommended 0..2)

  template <class V>
  void visit(V& v) {
    v("continuous", continuous,
      "continuous throttles Box(-1, 1, (2,)) [main, lateral] instead of "
      "Discrete(4)");
    v("gravity", gravity, "gravitational acceleration (m/s^2), strictly between -12 and 0");
    v("enable_wind", enable_wind,
      "apply wind (force) and turbulence (torque) while neither leg touches "
      "the ground");
    v("wind_power", wind_power, "maximum wind force; Gymnasium recommends 0 to 20");
    v("turbulence_power", turbulence_power,
      "maximum turbulence torque; Gymnasium recommends 0 to 2");
  }
};

class LunarLander : public Env {
 public:
  using Config = LunarLanderConfig;
  // gymnasium/envs/__init__.py registers LunarLander-v3 with
  // max_episode_steps=1000.
  static constexpr int kMaxEpisodeSteps = 1000;
  static constexpr int kObsSize = 8;
  static constexpr int kChunks = 11;  // terrain chunks (CHUNKS in reset())
  enum Action : int { kNoop = 0, kLeftEngine = 1, kMainEngine = 2, kRightEngine = 3 };

  // Throws std::invalid_argument unless -12 < gravity < 0 (Gymnasium's assert).
  explicit LunarLander(const Config& config = {});
  ~LunarLander() override;
  LunarLander(const LunarLander&) = delete;
  LunarLander& operator=(const LunarLander&) = delete;

  const Space& observation_space() const override { return observation_space_; }
  const Space& action_space() const override { return action_space_; }
  const Info& info() const override { return info_; }
  std::string id() const override {
    return config_.continuous ? "LunarLanderContinuous-v3" : "LunarLander-v3";
  }

  // Builds a new world (Gymnasium 1.0 does too, issue #728), the terrain, the
  // lander and its legs, pushes the lander with a random force, then takes one
  // no-op step whose observation is the first one (as Gymnasium's reset returns
  // self.step(0)[0]).
  void reset(std::optional<uint64_t> seed, std::span<float> obs) override;
  StepResult step(std::span<const float> action, std::span<float> obs) override;

  // viewport 600x400, metadata render_fps = FPS = 50.
  RenderSpec render_spec() const override { return {600, 400, 50.0}; }
  bool render(Frame& frame) const override;

  const Config& config() const { return config_; }

  // State for tests, baselines and rendering.
  bool leg_contact(int leg) const { return ground_contact_[leg]; }
  bool game_over() const { return game_over_; }
  bool lander_awake() const;
  double main_power() const { return m_power_; }  // engine throttles of the last step (0 = off)
  double side_power() const { return s_power_; }
  int wind_index() const { return wind_idx_; }
  int torque_index() const { return torque_idx_; }
  // Terrain (world units): chunk x positions, smoothed heights, helipad.
  const std::array<double, kChunks>& terrain_x() const { return chunk_x_; }
  const std::array<double, kChunks>& terrain_y() const { return smooth_y_; }
  double helipad_x1() const { return helipad_x1_; }
  double helipad_x2() const { return helipad_x2_; }
  double helipad_y() const { return helipad_y_; }
  // World-space outlines of the lander's hull (6 points) and each leg's box (4
  // points).
  std::array<std::array<double, 2>, 6> hull_outline() const;
  std::array<std::array<double, 2>, 4> leg_outline(int leg) const;

  // The Box2D world, its bodies and the contact listener (lunar_lander.cpp).
  struct Physics;
  friend struct Physics;

 private:
  void apply_wind();
  void fire_engines(std::span<const float> action);
  // Gymnasium's `state` list after a world step, in double (the observation is
  // its float32).
  std::array<double, kObsSize> state() const;

  Config config_;
  Space observation_space_;
  Space action_space_;
  Info info_;
  EnvSeeding seeding_;
  std::unique_ptr<Physics> physics_;  // null before the first reset
  bool game_over_ = false;
  std::array<bool, 2> ground_contact_{false, false};
  std::optional<double> prev_shaping_;
  double m_power_ = 0.0, s_power_ = 0.0;
  int wind_idx_ = 0, torque_idx_ = 0;
  std::array<double, kChunks> chunk_x_{}, smooth_y_{};
  double helipad_x1_ = 0, helipad_x2_ = 0, helipad_y_ = 0;
};

}  // namespace rlrun
