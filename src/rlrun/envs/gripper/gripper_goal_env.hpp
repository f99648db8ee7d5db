#pragma once
// GripperReach-v0, GripperPush-v0, GripperPickAndPlace-v0: panda-gym's goal-conditioned tasks
// (panda_gym/envs/tasks/{reach,push,pick_and_place}.py joined to the robot by
// panda_gym/envs/core.py RobotTaskEnv) on the Bullet gripper of GripperLift-v0
// (gripper_world.hpp). World frame, metres, the table top at z = 0, panda-gym's squares centred
// on the origin.
//
//   action  Reach, Push: Box(-1, 1, (3,)) dx, dy, dz of the grasp point, 5 cm per unit (panda
//           ee control: ee_displacement * 0.05), the fingers blocked closed (block_gripper).
//           PickAndPlace: Box(-1, 1, (4,)), the 4th the fingers' opening change, 0.2 m per unit
//           (panda.py: fingers_width + action[-1] * 0.2; +1 opens, -1 closes). The target is
//           clipped to the workspace (goal_workspace.hpp). One action = `substeps` physics
//           steps of 1/240 s (10: 24 Hz; panda-gym: 20 x 1/500 s = 25 Hz).
//   obs     Dict, keys sorted as Gymnasium does (achieved_goal, desired_goal, observation):
//             observation  robot: grasp point (3), its velocity (3), + finger opening (1) for
//                          PickAndPlace; task (Push, PickAndPlace): cube position (3), Euler
//                          angles roll pitch yaw as PyBullet's getEulerFromQuaternion (3),
//                          linear velocity (3), angular velocity (3). Reach 6, Push 18,
//                          PickAndPlace 19 floats, as panda-gym's.
//             achieved_goal  the grasp point (Reach) or the cube's centre (3)
//             desired_goal   the goal (3)
//   reward  compute_reward(achieved, desired): sparse (default) -(d > distance_threshold),
//           dense -d, with d the Euclidean distance, in float32 as panda-gym (step() returns
//           exactly what compute_reward gives for the observation it writes).
//   episode panda-gym's RobotTaskEnv.step: terminated = is_success = d < distance_threshold
//           (terminate_on_success: false gives Gymnasium-Robotics Fetch's never-terminating
//           episodes); truncated after the scenario's episode_steps (50).
//   reset   builds a new world from the scenario's ranges drawn from the env's seeded stream
//           (same seed, same episode bit for bit); the cube first, then the goal.
#include <array>
#include <memory>
#include <optional>
#include <span>
#include <string>

#include "rlrun/core/config_checks.hpp"
#include "rlrun/env.hpp"
#include "rlrun/env/goal_env.hpp"
#include "rlrun/env_seeding.hpp"
#include "rlrun/envs/gripper/goal_scenario.hpp"
#include "rlrun/envs/gripper/gripper_camera_observation.hpp"
#include "rlrun/envs/gripper/gripper_world.hpp"
#include "rlrun/info.hpp"
#include "rlrun/space.hpp"

namespace rlrun {

enum class GoalTask { kReach, kPush, kPickAndPlace };

class GripperGoalEnv : public Env, public GoalEnv {
 public:
  struct Config {
    std::string scenario;  // empty = the task's scenarios/grasp/{reach,push,pick_and_place}.yaml
    std::string reward_type = "sparse";
    double distance_threshold = 0.05;  // m
    bool terminate_on_success = true;  // panda-gym 3; false = Gymnasium-Robotics Fetch
    double palm_force = 30.0;
    double finger_force = 10.0;
    int substeps = 10;
    int solver_iterations = 20;
    // obs_type pixels: the `observation` key is the camera image; both: the state vector stays
    // `observation` and the image comes as `pixels`. The goals stay vectors (HER relabels them)
    // and the camera does not show the goal.
    GripperCameraConfig camera;

    template <class V>
    void visit(V& v) {
      v("scenario", scenario,
        "goal-task scenario file (scenarios/grasp/*.yaml); empty = the env's own");
      v("reward_type", reward_type, "sparse: -(d > distance_threshold); dense: -d",
        OneOf{{"sparse", "dense"}});
      v("distance_threshold", distance_threshold, "m: success when the goal is closer",
        in_range(0, 1).open_low());
      v("terminate_on_success", terminate_on_success,
        "end the episode on success (panda-gym) or never (Fetch)");
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

  static constexpr double kMovePerStep = 0.05;  // m per unit action (panda-gym's ee control)
  static constexpr double kGripPerStep = 0.2;   // m of opening per unit action (panda-gym)

  // Throws std::invalid_argument on bad settings, ConfigError or RuntimeFailure on a bad
  // scenario file.
  GripperGoalEnv(GoalTask task, const Config& config);
  ~GripperGoalEnv() override;

  const Space& observation_space() const override { return observation_space_; }
  const Space& action_space() const override { return action_space_; }
  const Info& info() const override { return info_; }
  std::string id() const override;

  void reset(std::optional<uint64_t> seed, std::span<float> obs) override;
  StepResult step(std::span<const float> action, std::span<float> obs) override;

  void compute_reward(const Eigen::Ref<const Eigen::MatrixXf>& achieved,
                      const Eigen::Ref<const Eigen::MatrixXf>& desired,
                      Eigen::Ref<Eigen::RowVectorXf> rewards) const override;

  // GripperLift's picture (gripper_scene_render.hpp) with the goal drawn as a green marker
  // (a sphere for Reach, the outline of the cube's target pose otherwise) and its shadow.
  RenderSpec render_spec() const override { return {480, 480, 24.0}; }
  bool render(Frame& frame) const override;

  GoalTask task() const { return task_; }
  const Config& config() const { return config_; }
  const GoalTaskScenario& scenario() const { return scenario_; }
  bool blocked_gripper() const { return task_ != GoalTask::kPickAndPlace; }
  int observation_size() const { return observation_size_; }
  // The running world (after reset), for the scripted policies and tests.
  const GripperWorld& world() const { return *world_; }
  const Vec3& goal() const { return goal_; }
  Vec3 achieved_goal() const;
  // The cube's centre when it rests on the table (Push, PickAndPlace).
  double resting_height() const { return resting_height_; }
  bool success() const { return success_; }
  // panda-gym's distance between two goals, from their float32 values as observed.
  static float distance(const float* a, const float* b);

 private:
  void write_observation(std::span<float> obs);
  void write_goals(std::span<float> obs) const;
  // Writes the observation, then success and info from its goals; returns their distance.
  float observe(std::span<float> obs);
  float reward_of(float d) const;

  GoalTask task_;
  Config config_;
  bool dense_;
  GoalTaskScenario scenario_;
  int observation_size_;
  Space observation_space_;
  Space action_space_;
  size_t at_achieved_, at_desired_, at_observation_;  // where each key starts in a flat obs
  GripperCameraObservation camera_;
  size_t at_pixels_ = 0;  // the image's start (obs_type pixels: at_observation_)
  Info info_;
  EnvSeeding seeding_;
  std::unique_ptr<GripperWorld> world_;
  Vec3 goal_{0, 0, 0};
  double resting_height_ = 0;
  bool success_ = false;
  int steps_ = 0;
  int key_success_, key_distance_;
};

class GripperReach : public GripperGoalEnv {
 public:
  using Config = GripperGoalEnv::Config;
  GripperReach() : GripperReach(Config{}) {}
  explicit GripperReach(const Config& config) : GripperGoalEnv(GoalTask::kReach, config) {}
};

class GripperPush : public GripperGoalEnv {
 public:
  using Config = GripperGoalEnv::Config;
  GripperPush() : GripperPush(Config{}) {}
  explicit GripperPush(const Config& config) : GripperGoalEnv(GoalTask::kPush, config) {}
};

class GripperPickAndPlace : public GripperGoalEnv {
 public:
  using Config = GripperGoalEnv::Config;
  GripperPickAndPlace() : GripperPickAndPlace(Config{}) {}
  explicit GripperPickAndPlace(const Config& config)
      : GripperGoalEnv(GoalTask::kPickAndPlace, config) {}
};

}  // namespace rlrun
