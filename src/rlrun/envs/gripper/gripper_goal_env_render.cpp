// The goal tasks' picture: the gripper scene (gripper_scene_render.hpp) from further back than
// GripperLift's camera, so the whole 30 cm goal square and Reach's 30 cm goal height are in
// view, and the goal as a green marker with its shadow on the table (which shows an in-air
// goal's height): panda-gym's target sphere (2 cm radius) for Reach, the outline of the cube
// at its target (twelve thin edges, so a cube arriving there stays visible) for Push and
// PickAndPlace. The cube is red, green on success.
#include <stdexcept>

#include "rlrun/envs/gripper/gripper_goal_env.hpp"
#include "rlrun/envs/gripper/gripper_scene_render.hpp"
#include "rlrun/frame.hpp"
#include "rlrun/render/rasterizer.hpp"

namespace rlrun {

namespace {

constexpr Rgb kGoalColor{40, 225, 40};
constexpr double kReachMarkerRadius = 0.02;  // panda-gym reach.py's target sphere
constexpr double kEdgeHalf = 0.002;          // m: half the thickness of the outline's edges

void draw_cube_outline(Rasterizer& raster, const Vec3& centre, double half) {
  // Four edges along each axis, at the corners of the other two.
  for (int axis = 0; axis < 3; ++axis)
    for (int corner = 0; corner < 4; ++corner) {
      GripperWorld::BoxPose edge;
      edge.rotation = {1, 0, 0, 0, 1, 0, 0, 0, 1};
      edge.centre = centre;
      edge.half = {kEdgeHalf, kEdgeHalf, kEdgeHalf};
      edge.half[axis] = half + kEdgeHalf;
      const int u = (axis + 1) % 3, v = (axis + 2) % 3;
      edge.centre[u] += (corner & 1 ? 1 : -1) * half;
      edge.centre[v] += (corner & 2 ? 1 : -1) * half;
      draw_box(raster, edge, kGoalColor);
    }
}

}  // namespace

bool GripperGoalEnv::render(Frame& frame) const {
  if (!world_) throw std::logic_error(id() + ": call reset() before render()");
  Rasterizer raster(frame);
  GripperCamera camera;
  camera.eye = {0.46f, -0.58f, 0.48f};
  camera.target = {0.0f, 0.0f, 0.11f};
  draw_gripper_scene(raster, frame, *world_, camera,
                     success_ ? Rgb{40, 180, 70} : Rgb{200, 40, 40});
  if (task_ == GoalTask::kReach) {
    draw_sphere_shadow(raster, goal_, kReachMarkerRadius);
    draw_sphere(raster, goal_, kReachMarkerRadius, kGoalColor);
  } else {
    const double half = world_->layout().cube_size / 2;
    GripperWorld::BoxPose target;
    target.centre = goal_;
    target.rotation = {1, 0, 0, 0, 1, 0, 0, 0, 1};
    target.half = {half, half, half};
    if (goal_[2] > resting_height_ + 1e-6) draw_box_shadow(raster, target);
    draw_cube_outline(raster, goal_, half);
  }
  return true;
}

}  // namespace rlrun
