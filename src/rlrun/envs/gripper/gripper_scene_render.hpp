#pragma once
// The gripper tasks' picture, shared by GripperLift-v0 (gripper_lift_render.cpp) and the goal
// tasks (gripper_goal_env_render.cpp): the table (a checkered square, for depth), the cube,
// the palm and fingers (greys), seen from the front-right and above like panda-gym's default
// camera, flat shaded by one directional light, each box casting a hard shadow on the table
// (its corners projected along the light onto the table plane, the convex hull filled dark:
// the planar projected shadow of Blinn, "Me and My (Fake) Shadow", 1988).
#include <Eigen/Core>
#include <span>

#include "rlrun/envs/gripper/gripper_world.hpp"
#include "rlrun/frame.hpp"
#include "rlrun/render/rasterizer.hpp"

namespace rlrun {

struct GripperCamera {
  Eigen::Vector3f eye{0.40f, -0.50f, 0.38f};
  Eigen::Vector3f target{0.0f, 0.0f, 0.09f};
  float fov_y = 0.85f;  // rad
  float near = 0.05f;   // m: the near clipping plane
};

// Sets the camera and light, clears to the sky, draws the table, every box's shadow and the
// boxes (the cube, if the world has one, in `cube_color`). Further shapes may follow.
void draw_gripper_scene(Rasterizer& raster, const Frame& frame, const GripperWorld& world,
                        const GripperCamera& camera, Rgb cube_color);

// A box of the world's kind, and its shadow on the table.
void draw_box(Rasterizer& raster, const GripperWorld::BoxPose& box, Rgb color);
void draw_box_shadow(Rasterizer& raster, const GripperWorld::BoxPose& box);
// A sphere (a 12 x 8 latitude-longitude mesh) and its shadow.
void draw_sphere(Rasterizer& raster, const Vec3& centre, double radius, Rgb color);
void draw_sphere_shadow(Rasterizer& raster, const Vec3& centre, double radius);

}  // namespace rlrun
