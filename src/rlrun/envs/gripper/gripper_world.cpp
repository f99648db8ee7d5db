#include "rlrun/envs/gripper/gripper_world.hpp"

#include <BulletDynamics/ConstraintSolver/btGeneric6DofSpring2Constraint.h>
#include <btBulletDynamicsCommon.h>

#include <algorithm>
#include <stdexcept>

namespace rlrun {

namespace {

constexpr double kShapeMargin = 0.001;  // m: Bullet's default 0.04 is near a finger's size
constexpr double kPalmMass = 1.0;       // kg; gravity-compensated like a robot arm's flange
constexpr double kFingerMass = 0.1;
constexpr double kPalmSpeed = 1.0;          // m/s the palm servo may reach (2 cm per 1/24 s step)
constexpr double kFingerSpeed = 0.25;       // m/s the fingers close at
constexpr double kContactDistance = 0.002;  // m: closer than this counts as touching

btVector3 bt(const Vec3& v) { return btVector3(v[0], v[1], v[2]); }
Vec3 vec(const btVector3& v) { return {v.x(), v.y(), v.z()}; }

}  // namespace

btRigidBody* GripperWorld::add_box(const Vec3& half, double mass, const Vec3& centre, double yaw,
                                   double friction, bool gravity) {
  auto shape = std::make_unique<btBoxShape>(bt(half));
  shape->setMargin(kShapeMargin);
  btVector3 inertia(0, 0, 0);
  if (mass > 0) shape->calculateLocalInertia(mass, inertia);
  btRigidBody::btRigidBodyConstructionInfo info(mass, nullptr, shape.get(), inertia);
  info.m_startWorldTransform.setIdentity();
  info.m_startWorldTransform.setOrigin(bt(centre));
  info.m_startWorldTransform.setRotation(btQuaternion(btVector3(0, 0, 1), yaw));
  info.m_friction = friction;
  auto body = std::make_unique<btRigidBody>(info);
  body->setActivationState(DISABLE_DEACTIVATION);  // nothing may fall asleep mid-grasp
  if (!gravity) body->setFlags(body->getFlags() | BT_DISABLE_WORLD_GRAVITY);
  world_->addRigidBody(body.get());
  if (!gravity) body->setGravity(btVector3(0, 0, 0));
  shapes_.push_back(std::move(shape));
  bodies_.push_back(std::move(body));
  return bodies_.back().get();
}

GripperWorld::GripperWorld(const Layout& layout) : layout_(layout) {
  collision_configuration_ = std::make_unique<btDefaultCollisionConfiguration>();
  dispatcher_ = std::make_unique<btCollisionDispatcher>(collision_configuration_.get());
  broadphase_ = std::make_unique<btDbvtBroadphase>();
  solver_ = std::make_unique<btSequentialImpulseConstraintSolver>();
  world_ = std::make_unique<btDiscreteDynamicsWorld>(dispatcher_.get(), broadphase_.get(),
                                                     solver_.get(), collision_configuration_.get());
  world_->setGravity(btVector3(0, 0, -9.81));
  btContactSolverInfo& solver_info = world_->getSolverInfo();
  solver_info.m_numIterations = layout.solver_iterations;
  solver_info.m_solverMode |= SOLVER_USE_2_FRICTION_DIRECTIONS;  // held boxes creep without it

  // The table: a static plane at z = 0.
  auto table_shape = std::make_unique<btStaticPlaneShape>(btVector3(0, 0, 1), 0);
  btRigidBody::btRigidBodyConstructionInfo table_info(0, nullptr, table_shape.get());
  table_info.m_friction = 1.0;
  auto table = std::make_unique<btRigidBody>(table_info);
  world_->addRigidBody(table.get());
  shapes_.push_back(std::move(table_shape));
  bodies_.push_back(std::move(table));

  if (layout.with_cube) {
    const double s = layout.cube_size / 2;
    cube_ = add_box({s, s, s}, layout.cube_mass, layout.cube_position, layout.cube_yaw,
                    layout.cube_friction, true);
  }

  // The palm, its centre kGraspBelowPalm above the grasp point, on a servo to the world.
  palm_start_ = {layout.grasp_point[0], layout.grasp_point[1],
                 layout.grasp_point[2] + kGraspBelowPalm};
  palm_ =
      add_box({kPalmHalf[0], kPalmHalf[1], kPalmHalf[2]}, kPalmMass, palm_start_, 0, 1.0, false);
  btTransform at_palm;
  at_palm.setIdentity();
  constraints_.push_back(std::make_unique<btGeneric6DofSpring2Constraint>(*palm_, at_palm));
  palm_servo_ = constraints_.back().get();
  palm_servo_->setLinearLowerLimit(btVector3(-1, -1, -1));  // a 2 m cube of travel
  palm_servo_->setLinearUpperLimit(btVector3(1, 1, 1));
  palm_servo_->setAngularLowerLimit(btVector3(0, 0, 0));  // rotation locked
  palm_servo_->setAngularUpperLimit(btVector3(0, 0, 0));
  for (int axis = 0; axis < 3; ++axis) {
    palm_servo_->enableMotor(axis, true);
    palm_servo_->setServo(axis, true);
    palm_servo_->setTargetVelocity(axis, kPalmSpeed);
    palm_servo_->setMaxMotorForce(axis, layout.palm_force);
    palm_servo_->setServoTarget(axis, 0);
  }
  world_->addConstraint(palm_servo_, true);

  // The fingers hang under the palm on prismatic servos along the palm's x axis; at opening
  // 0 their inner faces meet.
  const double finger_drop = kPalmHalf[2] + kFingerHalf[2];
  for (int f = 0; f < 2; ++f) {
    const double side = f == 0 ? -1.0 : 1.0;
    const double x = side * (layout.opening / 2 + kFingerHalf[0]);
    fingers_[f] =
        add_box({kFingerHalf[0], kFingerHalf[1], kFingerHalf[2]}, kFingerMass,
                {palm_start_[0] + x, palm_start_[1], palm_start_[2] - finger_drop}, 0, 1.0, false);
    btTransform in_palm, in_finger;
    in_palm.setIdentity();
    in_palm.setOrigin(btVector3(0, 0, -finger_drop));
    in_finger.setIdentity();
    constraints_.push_back(
        std::make_unique<btGeneric6DofSpring2Constraint>(*palm_, *fingers_[f], in_palm, in_finger));
    btGeneric6DofSpring2Constraint* slider = constraints_.back().get();
    const double inner = side * kFingerHalf[0], outer = side * (kMaxOpening / 2 + kFingerHalf[0]);
    slider->setLinearLowerLimit(btVector3(std::min(inner, outer), 0, 0));
    slider->setLinearUpperLimit(btVector3(std::max(inner, outer), 0, 0));
    slider->setAngularLowerLimit(btVector3(0, 0, 0));
    slider->setAngularUpperLimit(btVector3(0, 0, 0));
    slider->enableMotor(0, true);
    slider->setServo(0, true);
    slider->setTargetVelocity(0, kFingerSpeed);
    slider->setMaxMotorForce(0, layout.finger_force);
    slider->setServoTarget(0, x);
    world_->addConstraint(slider, true);  // no palm-finger collisions
    finger_servos_[f] = slider;
  }
}

GripperWorld::~GripperWorld() {
  for (auto& c : constraints_) world_->removeConstraint(c.get());
  for (auto& b : bodies_) world_->removeRigidBody(b.get());
}

void GripperWorld::command(const Vec3& grasp_point_target, double opening_target) {
  for (int axis = 0; axis < 3; ++axis) {
    const double palm_target = grasp_point_target[axis] + (axis == 2 ? kGraspBelowPalm : 0.0);
    palm_servo_->setServoTarget(axis, palm_target - palm_start_[axis]);
  }
  const double half = std::clamp(opening_target, 0.0, kMaxOpening) / 2 + kFingerHalf[0];
  finger_servos_[0]->setServoTarget(0, -half);
  finger_servos_[1]->setServoTarget(0, half);
}

void GripperWorld::step(int substeps) {
  for (int i = 0; i < substeps; ++i) world_->stepSimulation(kTimeStep, 1, kTimeStep);
}

Vec3 GripperWorld::grasp_point() const {
  const btVector3 p = palm_->getCenterOfMassPosition();
  return {p.x(), p.y(), p.z() - kGraspBelowPalm};
}

Vec3 GripperWorld::palm_velocity() const { return vec(palm_->getLinearVelocity()); }

double GripperWorld::opening() const {
  const btVector3 across =
      fingers_[1]->getCenterOfMassPosition() - fingers_[0]->getCenterOfMassPosition();
  const btVector3 palm_x = palm_->getCenterOfMassTransform().getBasis().getColumn(0);
  return across.dot(palm_x) - 2 * kFingerHalf[0];
}

const btRigidBody& GripperWorld::cube() const {
  if (!cube_) throw std::logic_error("GripperWorld: this world has no cube (Layout::with_cube)");
  return *cube_;
}

Vec3 GripperWorld::cube_position() const { return vec(cube().getCenterOfMassPosition()); }

std::array<double, 4> GripperWorld::cube_orientation() const {
  const btQuaternion q = cube().getOrientation();
  return {q.x(), q.y(), q.z(), q.w()};
}

Vec3 GripperWorld::cube_velocity() const { return vec(cube().getLinearVelocity()); }
Vec3 GripperWorld::cube_angular_velocity() const { return vec(cube().getAngularVelocity()); }

std::array<bool, 2> GripperWorld::finger_contacts() const {
  std::array<bool, 2> touching{false, false};
  if (!cube_) return touching;
  for (int i = 0; i < dispatcher_->getNumManifolds(); ++i) {
    const btPersistentManifold* manifold = dispatcher_->getManifoldByIndexInternal(i);
    const btCollisionObject* a = manifold->getBody0();
    const btCollisionObject* b = manifold->getBody1();
    for (int f = 0; f < 2; ++f) {
      if (!((a == fingers_[f] && b == cube_) || (a == cube_ && b == fingers_[f]))) continue;
      for (int j = 0; j < manifold->getNumContacts(); ++j)
        if (manifold->getContactPoint(j).getDistance() <= kContactDistance) touching[f] = true;
    }
  }
  return touching;
}

GripperWorld::BoxPose GripperWorld::pose_of(const btRigidBody* body, const Vec3& half) const {
  BoxPose pose;
  const btTransform& t = body->getCenterOfMassTransform();
  pose.centre = vec(t.getOrigin());
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) pose.rotation[3 * r + c] = t.getBasis()[r][c];
  pose.half = half;
  return pose;
}

GripperWorld::BoxPose GripperWorld::palm_pose() const {
  return pose_of(palm_, {kPalmHalf[0], kPalmHalf[1], kPalmHalf[2]});
}

std::array<GripperWorld::BoxPose, 2> GripperWorld::finger_poses() const {
  const Vec3 half{kFingerHalf[0], kFingerHalf[1], kFingerHalf[2]};
  return {pose_of(fingers_[0], half), pose_of(fingers_[1], half)};
}

GripperWorld::BoxPose GripperWorld::cube_pose() const {
  const double s = layout_.cube_size / 2;
  return pose_of(&cube(), {s, s, s});
}

}  // namespace rlrun
