#pragma once
// MuJoCo's own renderer (mjv_updateScene, mjr_render, mjr_readPixels) on an offscreen OpenGL
// context (offscreen_gl_context.hpp): Gymnasium 1.0's MujocoRenderer in render_mode="rgb_array"
// (gymnasium/envs/mujoco/mujoco_rendering.py, OffScreenViewer):
//
//   scene    mjv_makeScene with room for 1000 geoms (max_geom), MuJoCo's default visual options
//   context  mjr_makeContext with 150% fonts, drawing into its offscreen framebuffer
//            (mjFB_OFFSCREEN) of the frame's size (Gymnasium sets the model's
//            vis.global.offwidth / offheight to its width / height; the env's model is shared
//            and read-only, so the context is made from a copy that carries the size)
//   camera   initial_camera() below
//   pixels   mjr_readPixels, whose rows run bottom-up, flipped (Gymnasium's rgb_img[::-1]) into
//            the frame
//
// An env makes its renderer at its first render() (training never makes one) and remakes the
// GL buffers when asked for a frame of another size. Rendering makes the renderer's GL context
// current for one frame only (offscreen_gl_context.hpp), so any thread may render, and several
// envs in one thread render in turn.
#include <mujoco/mujoco.h>

#include <memory>
#include <vector>

#include "rlrun/envs/mujoco/default_camera.hpp"
#include "rlrun/envs/mujoco/offscreen_gl_context.hpp"
#include "rlrun/frame.hpp"

namespace rlrun::mujoco {

// Gymnasium's camera: the model's camera named "track" when it has one (a fixed camera: Gymnasium
// looks that name up by default and renders from it), else the free camera that
// OffScreenViewer._init_camera sets up (lookat = the median of the geoms' positions in `data`,
// distance = the model's extent) with the task's DEFAULT_CAMERA_CONFIG over it. A trackbodyid in
// that configuration is set, as Gymnasium sets it, but a free camera does not follow a body.
mjvCamera initial_camera(const mjModel& model, const mjData& data, const DefaultCamera& config);

class MujocoRenderer {
 public:
  // `data`: the state at the first render, where the free camera looks.
  MujocoRenderer(const mjModel& model, const mjData& data, const DefaultCamera& camera);
  ~MujocoRenderer();
  MujocoRenderer(const MujocoRenderer&) = delete;
  MujocoRenderer& operator=(const MujocoRenderer&) = delete;

  // Draws `data`'s state into the whole `frame`. Throws RuntimeFailure when OpenGL or MuJoCo's
  // renderer fails. mjv_updateScene takes mjData* but changes nothing of the state.
  void render(const mjModel& model, mjData& data, Frame& frame);

  const char* gl_platform() const { return gl_->platform(); }

 private:
  struct Scene {
    Scene(const mjModel& model, int max_geoms);
    ~Scene();
    mjvScene scene;
  };

  void make_context(const mjModel& model, int width, int height);

  std::unique_ptr<OffscreenGlContext> gl_;
  Scene scene_;
  mjvCamera camera_;
  mjvOption options_;
  mjvPerturb perturb_;
  mjrContext context_;
  int width_ = 0, height_ = 0;  // of context_'s buffers; 0 until made
  std::vector<unsigned char> rgb_;
};

}  // namespace rlrun::mujoco
