#pragma once
// Grasp2D-v0: the course's SimpleGraspEnv (a 2D grasp task built from scratch), in C++.
// An arm moves on the unit square [0,1]^2 in steps of `step_size`; an object sits at a fixed
// point. The agent succeeds by closing the gripper within `success_threshold` of the object
// and fails by moving the arm out of the workspace. Both end the episode (terminated); the
// registered TimeLimit truncates after 100 steps (the course's `max_steps`; set it with
// `env.max_episode_steps`: as in Gymnasium, only TimeLimit truncates for time).
//
//   observation  Box(0, 1, (6,), float32): arm x, arm y, object x, object y,
//                gripper closed (0/1), grasped (0/1)
//   action       Discrete(6): 0 left, 1 right, 2 up, 3 down, 4 open, 5 close
//   reward       success_reward on a grasp, -failure_penalty on leaving the workspace,
//                otherwise -step_penalty - distance_scale * |arm - object| (after the step)
//   info         is_success, is_failure (0/1 on every step), action (the index taken; its
//                name is action_name(index)), distance (arm to object)
#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "rlrun/env.hpp"
#include "rlrun/env_seeding.hpp"
#include "rlrun/info.hpp"
#include "rlrun/space.hpp"

namespace rlrun {

class Grasp2D : public Env {
 public:
  struct Config {
    double step_size = 0.05;           // arm displacement per move action
    double success_threshold = 0.05;   // max arm-object distance at which closing grasps
    double success_reward = 10.0;      // reward of the grasping step
    double failure_penalty = 10.0;     // reward -failure_penalty when the arm leaves [0,1]^2
    double step_penalty = 0.01;        // constant cost of every other step
    double distance_scale = 0.1;       // shaping: -distance_scale * distance every other step
    double spawn_margin = 0.1;         // random starts lie in [margin, 1 - margin]^2
    std::vector<double> arm_start;     // fixed arm start [x, y]; empty = random
    std::vector<double> object_start;  // fixed object position [x, y]; empty = random

    template <class V>
    void visit(V& v) {
      v("step_size", step_size, "arm displacement per move action");
      v("success_threshold", success_threshold,
        "closing the gripper within this distance of the object grasps it (success)");
      v("success_reward", success_reward, "reward of the step that grasps the object");
      v("failure_penalty", failure_penalty,
        "the step that moves the arm out of [0,1]^2 gets reward -failure_penalty");
      v("step_penalty", step_penalty, "constant cost of every other step");
      v("distance_scale", distance_scale,
        "every other step costs distance_scale * (arm-object distance)");
      v("spawn_margin", spawn_margin,
        "random arm and object positions are drawn in [margin, 1 - margin]^2");
      v("arm_start", arm_start, "fixed arm start [x, y] for every reset; [] = random");
      v("object_start", object_start, "fixed object position [x, y] for every reset; [] = random");
    }
  };

  enum Action : int { kLeft = 0, kRight, kUp, kDown, kOpen, kClose, kNumActions };

  // Gymnasium's reset(options=...): positions that override this reset's random draw (the
  // draw still happens, so the RNG stream does not depend on the options).
  struct ResetOptions {
    std::optional<std::array<double, 2>> arm;
    std::optional<std::array<double, 2>> object;
  };

  // The course env's max_steps, registered as the TimeLimit of Grasp2D-v0.
  static constexpr int kMaxEpisodeSteps = 100;

  Grasp2D() : Grasp2D(Config{}) {}
  // Throws std::invalid_argument on a non-positive step size or threshold, a margin outside
  // [0, 0.5], or a fixed position that is not two numbers inside [0,1].
  explicit Grasp2D(const Config& config);

  const Space& observation_space() const override { return observation_space_; }
  const Space& action_space() const override { return action_space_; }
  const Info& info() const override { return info_; }
  std::string id() const override { return "Grasp2D-v0"; }

  void reset(std::optional<uint64_t> seed, std::span<float> obs) override;
  void reset(std::optional<uint64_t> seed, const ResetOptions& options, std::span<float> obs);
  StepResult step(std::span<const float> action, std::span<float> obs) override;

  bool can_save_state() const override { return true; }
  void write_state(StateWriter& out) const override;
  void read_state(const StateReader& in) override;

  RenderSpec render_spec() const override { return {kRenderSize, kRenderSize, 10.0}; }
  bool render(Frame& frame) const override;
  bool render_observation(std::span<const float> obs, Frame& frame) const override;

  // "left", "right", "up", "down", "open", "close".
  static const char* action_name(int action);

  const Config& config() const { return config_; }
  std::array<double, 2> arm() const { return {arm_x_, arm_y_}; }
  std::array<double, 2> object() const { return {object_x_, object_y_}; }
  bool gripper_closed() const { return gripper_closed_; }
  bool grasped() const { return grasped_; }
  double distance() const;

 private:
  static constexpr int kRenderSize = 500;

  void write_observation(std::span<float> obs) const;

  Config config_;
  Space observation_space_;
  Space action_space_;
  Info info_;
  EnvSeeding seeding_;  // Gymnasium seeding rules + the env's Rng
  int key_success_, key_failure_, key_action_, key_distance_;
  bool has_state_ = false;
  double arm_x_ = 0, arm_y_ = 0, object_x_ = 0, object_y_ = 0;
  bool gripper_closed_ = false;
  bool grasped_ = false;
  int last_action_ = -1;  // for render(); -1 before the first step
};

}  // namespace rlrun
