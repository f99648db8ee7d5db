#pragma once
// GripperLift-v0 / GripperLiftEasy-v0: the course's grasp problem in 3D on Bullet physics
// (gripper_world.hpp). A parallel-jaw gripper above a table must reach a cube, close on it and
// lift it 5 cm. Anchors: robosuite's Lift task (its staged reward) and panda-gym (PyBullet).
//
//   action  Box(-1, 1, (4,)): dx, dy, dz of the grasp point, 2 cm per unit (the servo target
//           is the current position plus the move, clipped to the workspace), and the grip:
//           -1 fully open ... +1 closed (the fingers' target opening; they squeeze with at
//           most finger_force). One action = `substeps` physics steps of 1/240 s (10: 24 Hz).
//   obs     Box(26): grasp point (3) and palm velocity (3), finger opening and its rate (2),
//           cube position (3), orientation quaternion x y z w (4), linear and angular
//           velocity (6), cube minus grasp point (3), one contact flag per finger (2). World
//           frame, metres, the table top at z = 0. With obs_type pixels: a camera image
//           instead, both: Dict{pixels, state} (gripper_camera_observation.hpp).
//   reward  robosuite Lift's staged shaping (robosuite/environments/manipulation/lift.py):
//           reach 1 - tanh(10 d) (d = |cube - grasp point|), + 0.25 while both fingers touch
//           the cube, + lift progress min(1, rise / 5 cm) while they do; 2.25 (the maximum)
//           on success = the cube >= 5 cm above its resting height while both fingers hold it.
//   episode `episode_steps` decisions (scenario; 50), then truncated. No termination on
//           success: a policy that stalls after a success would otherwise be paid for
//           stopping; info.is_success says whether the cube is up at this step.
//   reset   builds a new world from the scenario's ranges drawn from the env's stream, so the
//           same seed gives the same episode bit for bit.
#include <array>
#include <memory>
#include <optional>
#include <span>
#include <string>

#include "rlrun/core/config_checks.hpp"
#include "rlrun/env.hpp"
#include "rlrun/env_seeding.hpp"
#include "rlrun/envs/gripper/grasp_scenario.hpp"
#include "rlrun/envs/gripper/gripper_camera_observation.hpp"
#include "rlrun/envs/gripper/gripper_world.hpp"
#include "rlrun/info.hpp"
#include "rlrun/space.hpp"

namespace rlrun {

class GripperLift : public Env {
 public:
  struct Config {
    std::string scenario;      // empty = the variant's: scenarios/grasp/lift.yaml or lift_easy.yaml
    double palm_force = 30.0;  // N per axis of the palm servo
    double finger_force = 10.0;  // N per finger
    int substeps = 10;           // physics steps of 1/240 s per action
    int solver_iterations = 20;
    GripperCameraConfig camera;  // obs_type, camera, image_size

    template <class V>
    void visit(V& v) {
      v("scenario", scenario,
        "grasp scenario file (scenarios/grasp/*.yaml); empty = the env's own");
      v("palm_force", palm_force, "N per axis the palm servo may push with (~30: stronger slips)",
        in_range(0, 10000).open_low());
      v("finger_force", finger_force, "N each finger squeezes with at most (>= 5)",
        in_range(0, 10000).open_low());
      v("substeps", substeps, "physics steps of 1/240 s per action", in_range(1, 1000));
      v("solver_iterations", solver_iterations, "Bullet solver iterations per step (10-20)",
        in_range(1, 1000));
      camera.visit(v);
    }
  };

  static constexpr int kObsSize = 26;
  static constexpr double kMovePerStep = 0.02;  // m per unit action
  static constexpr double kLiftHeight = 0.05;   // m above the resting height = success

  GripperLift() : GripperLift(Config{}) {}
  // Throws std::invalid_argument on non-positive forces or substeps, ConfigError or
  // RuntimeFailure on a bad scenario file.
  explicit GripperLift(const Config& config, bool easy = false);
  ~GripperLift() override;

  const Space& observation_space() const override { return observation_space_; }
  const Space& action_space() const override { return action_space_; }
  const Info& info() const override { return info_; }
  std::string id() const override { return easy_ ? "GripperLiftEasy-v0" : "GripperLift-v0"; }

  void reset(std::optional<uint64_t> seed, std::span<float> obs) override;
  StepResult step(std::span<const float> action, std::span<float> obs) override;

  // A 3D view of the table, cube, palm and fingers with shadows (gripper_lift_render.cpp),
  // through render/rasterizer; one frame per action.
  RenderSpec render_spec() const override { return {480, 480, 24.0}; }
  bool render(Frame& frame) const override;

  const GraspScenario& scenario() const { return scenario_; }
  // The running world (after reset), for the scripted policy and tests.
  const GripperWorld& world() const { return *world_; }
  double resting_height() const { return resting_height_; }
  bool success() const { return success_; }

 private:
  void write_observation(std::span<float> obs);
  double reward_and_success();

  Config config_;
  bool easy_;
  GraspScenario scenario_;
  GripperCameraObservation camera_;
  Space observation_space_;
  Space action_space_;
  Info info_;
  EnvSeeding seeding_;
  std::unique_ptr<GripperWorld> world_;
  double resting_height_ = 0;
  double last_opening_ = 0;
  double opening_rate_ = 0;
  std::array<bool, 2> touching_{false, false};  // each finger on the cube, after this step
  bool success_ = false;
  int steps_ = 0;
  int key_success_, key_grasped_, key_lift_, key_distance_;
};

// The easy variant: the same env with scenarios/grasp/lift_easy.yaml by default.
class GripperLiftEasy : public GripperLift {
 public:
  using Config = GripperLift::Config;
  GripperLiftEasy() : GripperLiftEasy(Config{}) {}
  explicit GripperLiftEasy(const Config& config) : GripperLift(config, true) {}
};

}  // namespace rlrun
