#pragma once
// BipedalWalker-v3 and BipedalWalkerHardcore-v3: Gymnasium 1.0's
// gymnasium/envs/box2d/bipedal_walker.py on Box2D 2.4 (Gymnasium runs pybox2d 2.3; what that
// changes is in docs/box2d.md). A four-joint walker (hull, two upper and two lower legs) must
// cross TERRAIN_LENGTH steps of terrain; hardcore adds stumps, stairs and pits.
//
//   observation  Box(24,) float32 with Gymnasium's bounds: hull angle, 2 * angular velocity /
//                FPS, 0.3 * velocity * (viewport / SCALE) / FPS (x, y), then per leg the hip
//                angle, hip speed / SPEED_HIP, knee angle + 1, knee speed / SPEED_KNEE and the
//                lower leg's ground contact (0/1), then 10 lidar fractions (1 = nothing hit)
//   action       Box(-1, 1, (4,)): hip 0, knee 0, hip 1, knee 1. Torque control: the motor
//                turns toward sign(a) * SPEED_{HIP,KNEE} with at most MOTORS_TORQUE * |a|
//   reward       the change of 130 * hull x / SCALE - 5 * |hull angle|, minus
//                0.00035 * MOTORS_TORQUE * clip(|a_i|, 0, 1) per motor; -100 instead when the
//                hull touches the ground or leaves the terrain on the left
//   terminated   hull contact (game over), hull x < 0, or hull x past the end of the terrain
//   time limit   1600 steps (BipedalWalker-v3), 2000 (BipedalWalkerHardcore-v3), by TimeLimit
// The Box2D world is rebuilt at every reset (terrain from the env's RNG); step() only steps it.
#include <box2d/box2d.h>
#include <array>
#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <string>

#include "rlrun/env.hpp"
#include "rlrun/env_seeding.hpp"
#include "rlrun/envs/bipedal_walker/walker_constants.hpp"
#include "rlrun/envs/bipedal_walker/walker_terrain.hpp"
#include "rlrun/info.hpp"
#include "rlrun/space.hpp"

namespace rlrun {

class BipedalWalker : public Env {
 public:
  struct Config {
    bool hardcore = false;  // Gymnasium's kwarg: stumps, stairs and pits between grass

    template <class V>
    void visit(V& v) {
      v("hardcore", hardcore,
        "add obstacles (stumps, stairs, pits) to the terrain, as BipedalWalkerHardcore-v3");
    }
  };

  BipedalWalker() : BipedalWalker(Config{}) {}
  explicit BipedalWalker(const Config& config);
  ~BipedalWalker() override;

  const Space& observation_space() const override { return observation_space_; }
  const Space& action_space() const override { return action_space_; }
  const Info& info() const override { return info_; }
  std::string id() const override;

  void reset(std::optional<uint64_t> seed, std::span<float> obs) override;
  StepResult step(std::span<const float> action, std::span<float> obs) override;

  RenderSpec render_spec() const override {
    return {walker::kViewportW, walker::kViewportH, walker::kFps};
  }
  bool render(Frame& frame) const override;

  // For tests and the scripted controller.
  const Config& config() const { return config_; }
  const walker::Terrain& terrain() const { return terrain_; }
  b2Vec2 hull_position() const { return hull_->GetPosition(); }
  double hull_angle() const { return hull_->GetAngle(); }
  bool game_over() const { return game_over_; }
  bool leg_contact(int leg) const { return ground_contact_[static_cast<size_t>(leg)]; }
  // Steps since the last reset (0 right after it; reset's own zero-action step not counted).
  int episode_steps() const { return episode_steps_; }
  // The last shaping value, 130 * x / SCALE - 5 * |angle| (Gymnasium's prev_shaping).
  double shaping() const { return prev_shaping_; }
  // The end points of ray i of the last lidar scan (p1 = hull, p2 = its hit or its far end).
  std::array<b2Vec2, 2> lidar_ray(int i) const;

 private:
  class ContactDetector;
  class LidarCallback;

  void build_world();
  // Gymnasium's step() body after the actions are set: world step, lidar, observation,
  // reward and termination. `action` is used only for the torque cost.
  StepResult advance(std::span<const float> action, std::span<float> obs);
  void scan_lidar();

  Config config_;
  Space observation_space_;
  Space action_space_;
  Info info_;
  EnvSeeding seeding_;

  walker::Terrain terrain_;
  std::unique_ptr<b2World> world_;
  std::unique_ptr<ContactDetector> contacts_;
  b2Body* hull_ = nullptr;
  std::array<b2Body*, 4> legs_{};             // upper 0, lower 0, upper 1, lower 1
  std::array<b2RevoluteJoint*, 4> joints_{};  // hip 0, knee 0, hip 1, knee 1
  std::array<bool, 4> ground_contact_{};      // per legs_ entry (lower legs report)
  std::array<float, walker::kLidarRays> lidar_fraction_{};
  std::array<b2Vec2, walker::kLidarRays> lidar_end_{};
  b2Vec2 lidar_start_{0, 0};
  bool game_over_ = false;
  bool has_prev_shaping_ = false;
  double prev_shaping_ = 0.0;
  int episode_steps_ = 0;
};

}  // namespace rlrun
