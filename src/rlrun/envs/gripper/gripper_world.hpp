#pragma once
// The physics of the 3D grasp task, on Bullet 3.24 (Debian's libbullet-dev): a table (plane
// at z = 0), a cube, and a parallel-jaw gripper — a palm that a 6-DoF servo constraint moves
// in Cartesian space (rotation locked, force limited) and two fingers on prismatic servos that
// open and close together (force limited, so a closed grip squeezes with at most that force).
// Physics at 240 Hz (PyBullet's default step, as panda-gym uses).
//
// Facts from the feasibility study this follows (issue 8): Bullet's default solver lets a held
// box creep ~19 mm/s and lifts fail, so friction is solved in two directions
// (SOLVER_USE_2_FRICTION_DIRECTIONS); a palm servo stronger than ~30 N made heavier boxes slip;
// fingers need >= 5 N and friction >= 0.2; 10-20 solver iterations suffice.
//
// A world is built whole by its constructor, in a fixed order, so two worlds built from the
// same Layout step bit-identically: resetting the env builds a new one.
#include <array>
#include <memory>
#include <vector>

class btBroadphaseInterface;
class btCollisionConfiguration;
class btCollisionDispatcher;
class btConstraintSolver;
class btDiscreteDynamicsWorld;
class btRigidBody;
class btCollisionShape;
class btGeneric6DofSpring2Constraint;

namespace rlrun {

using Vec3 = std::array<double, 3>;

class GripperWorld {
 public:
  // Gripper geometry (m). The grasp point — the "fingertip centre" the task measures from —
  // sits kGraspBelowPalm under the palm's centre, between the fingers 1.5 cm above their tips.
  static constexpr double kPalmHalf[3] = {0.06, 0.02, 0.01};
  static constexpr double kFingerHalf[3] = {0.005, 0.015, 0.03};
  static constexpr double kGraspBelowPalm = 0.055;
  static constexpr double kMaxOpening = 0.09;  // between the fingers' inner faces
  static constexpr double kTimeStep = 1.0 / 240.0;

  struct Layout {
    double cube_size = 0.05, cube_mass = 0.1, cube_friction = 1.0;
    Vec3 cube_position{0, 0, 0.025};  // centre
    double cube_yaw = 0;
    Vec3 grasp_point{0, 0, 0.15};  // where the fingertips' centre starts
    double opening = kMaxOpening;  // fingers start this far apart
    double palm_force = 30.0;      // N, per axis (the study's limit)
    double finger_force = 10.0;    // N, per finger (>= 5 N)
    int solver_iterations = 20;
    // Without the cube (GripperReach-v0): the same table, palm and fingers, nothing to touch.
    // Worlds with the cube are built exactly as before the option existed.
    bool with_cube = true;
  };

  explicit GripperWorld(const Layout& layout);
  ~GripperWorld();
  GripperWorld(const GripperWorld&) = delete;
  GripperWorld& operator=(const GripperWorld&) = delete;

  // Servo targets: where the grasp point should go, how far apart the fingers should be.
  void command(const Vec3& grasp_point_target, double opening_target);
  void step(int substeps);  // each kTimeStep long

  Vec3 grasp_point() const;
  Vec3 palm_velocity() const;
  double opening() const;  // between the inner faces
  bool has_cube() const { return cube_ != nullptr; }
  // The cube's state; these throw std::logic_error in a world built without it.
  Vec3 cube_position() const;
  std::array<double, 4> cube_orientation() const;  // quaternion x, y, z, w
  Vec3 cube_velocity() const;
  Vec3 cube_angular_velocity() const;
  // Whether each finger (left = -x, right = +x) touches the cube now (never without one).
  std::array<bool, 2> finger_contacts() const;
  const Layout& layout() const { return layout_; }

  // Pose of each box for drawing: centre, rotation (row-major 3x3), half extents.
  struct BoxPose {
    Vec3 centre;
    std::array<double, 9> rotation;
    Vec3 half;
  };
  BoxPose palm_pose() const;
  std::array<BoxPose, 2> finger_poses() const;
  BoxPose cube_pose() const;

 private:
  btRigidBody* add_box(const Vec3& half, double mass, const Vec3& centre, double yaw,
                       double friction, bool gravity);
  BoxPose pose_of(const btRigidBody* body, const Vec3& half) const;
  const btRigidBody& cube() const;

  Layout layout_;
  std::unique_ptr<btCollisionConfiguration> collision_configuration_;
  std::unique_ptr<btCollisionDispatcher> dispatcher_;
  std::unique_ptr<btBroadphaseInterface> broadphase_;
  std::unique_ptr<btConstraintSolver> solver_;
  std::unique_ptr<btDiscreteDynamicsWorld> world_;
  std::vector<std::unique_ptr<btCollisionShape>> shapes_;
  std::vector<std::unique_ptr<btRigidBody>> bodies_;
  std::vector<std::unique_ptr<btGeneric6DofSpring2Constraint>> constraints_;
  btRigidBody* palm_ = nullptr;
  btRigidBody* fingers_[2] = {nullptr, nullptr};
  btRigidBody* cube_ = nullptr;
  btGeneric6DofSpring2Constraint* palm_servo_ = nullptr;
  btGeneric6DofSpring2Constraint* finger_servos_[2] = {nullptr, nullptr};
  Vec3 palm_start_{0, 0, 0};
};

}  // namespace rlrun
